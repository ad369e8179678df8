// A run-time axis (0, 1, 2) as a compile-time one: kernels instantiated per sweep axis have
// constant index steps along it (docs/numerics.md, "One cycle", item 5).
#pragma once
#include <type_traits>

namespace mp {

// Calls f(std::integral_constant<int, D>{}) with D == d; f reads the axis as
// decltype(a)::value. (Host code: f launches the kernels, which are defined outside it.)
template <class F>
void with_axis(int d, F&& f) {
  if (d == 0)
    f(std::integral_constant<int, 0>{});
  else if (d == 1)
    f(std::integral_constant<int, 1>{});
  else
    f(std::integral_constant<int, 2>{});
}

}  // namespace mp
