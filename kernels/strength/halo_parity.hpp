// The halo parities of a stress set's 7 carried quantities, shared by the dense sets' halo fields
// (module.cpp) and the pooled sets' halo (remap.cpp, Strength::exchange_compact).
#pragma once

namespace mp::strength {

// Halo parities of the 7 carried quantities (xx, yy, zz, xy, yz, zx, plastic strain): the shear
// components change sign under the two reflections that flip them.
inline constexpr int kParity[7][3] = {{1, 1, 1},   {1, 1, 1},   {1, 1, 1}, {-1, -1, 1},
                                      {1, -1, -1}, {-1, 1, -1}, {1, 1, 1}};

}  // namespace mp::strength
