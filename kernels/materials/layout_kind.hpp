// How a multi-material scene stores its per-material state (kernels/materials/layout.hpp):
// every material in every cell (dense, the paper's layout), or pure cells in place and the
// mixed ones in a compact list (compact).
#pragma once

namespace mp::mat {

enum class LayoutKind { Dense, Compact };

}  // namespace mp::mat
