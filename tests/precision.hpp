// Tolerances for the precision of this build's fields (-DMINIPAGOSA_PRECISION=double|float).
//
// Two kinds of bound appear in the tests:
// - round-off bounds (conservation, symmetry, agreement of two code paths), written for double
//   and scaled by the ratio of the machine epsilons (2^29 for float): `roundoff(1e-13)`;
// - accuracy bounds measured in each precision, where float round-off, not the scheme, sets
//   the error (finite differences of p, exact solvers built on the EOS): `by_precision(d, f)`,
//   with the float value written beside the value observed in a float build.
// Scheme errors (L1 norms, wave positions, convergence orders) are the same in both and keep
// one bound.
#pragma once
#include <cfloat>
#include <limits>
#include <type_traits>

#include "core/types.hpp"

namespace mp::test {

inline constexpr bool kFloat = std::is_same_v<Real, float>;

// Machine epsilon of the fields.
inline constexpr double kEps = double(std::numeric_limits<Real>::epsilon());

// A round-off bound written for double, scaled to this build's Real.
inline constexpr double roundoff(double bound_for_double) {
  return bound_for_double * (kEps / DBL_EPSILON);
}

// A bound measured separately in each precision.
inline constexpr double by_precision(double for_double, double for_float) {
  return kFloat ? for_float : for_double;
}

// Relative change of total energy over `cycles` cycles in a closed box, with the KE fix
// returning the remap's whole discrepancy (docs/numerics.md, cycle step 6): every sweep rounds
// each cell's energy a few times (the p dV update, the remap quotient, the KE fix's share), each
// by at most eps/2 of it, and each node's kinetic energy likewise; k = 8 roundings of one sign
// per sweep, 3 sweeps per cycle, is the worst case. Observed 0.4x (Sedov 48^3) to 1/90 (closed
// Sod) of it in double: roundings of mixed sign cancel.
inline constexpr double energy_roundoff(long cycles) {
  return 8 * kEps * 3 * double(cycles);
}

}  // namespace mp::test
