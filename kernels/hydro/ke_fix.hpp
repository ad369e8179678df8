// The KE fix's point functions (DeBar's correction; docs/numerics.md, "One cycle", item 6): a
// cell's share of its nodes' kinetic-energy losses, how a node's loss is stored, the redo flag,
// the floor's unpaid energy, and the corner sum of a node field.
#pragma once

#include "core/types.hpp"

namespace mp::hydro {

// Specific internal energy a cell of mass m and internal energy w = m max(e, 0) takes from the
// KE fix (issue #16; docs/numerics.md, "One cycle", item 6): each of its 8 nodes holds, in
// `kel`, either its kinetic-energy loss L >= 0, of which every cell takes 1/8, or, where the
// remap made kinetic energy (L < 0), L over the 8 cells' w summed, so that each cell pays the
// same fraction of its own internal energy — a cold cell beside hot ones pays little, and the
// 8 cells together pay L: total energy is kept.
template <class Corner>
KOKKOS_INLINE_FUNCTION Real ke_fix_share_of(const Corner& kel, Real m, Real w) {
  // separate sums, the two being in different units, over the corners in the order a, b, c; as
  // selects, not branches, so that a column loop vectorizes (adding +0 to the other sum leaves
  // it bit for bit)
  Real gain = 0, frac = 0;
  auto add = [&](Real x) {
    const bool pos = x >= 0;
    gain += pos ? x : Real(0);
    frac += pos ? Real(0) : x;
  };
  add(kel(0, 0, 0));
  add(kel(1, 0, 0));
  add(kel(0, 1, 0));
  add(kel(1, 1, 0));
  add(kel(0, 0, 1));
  add(kel(1, 0, 1));
  add(kel(0, 1, 1));
  add(kel(1, 1, 1));
  return (Real(0.125) * gain + frac * w) / m;
}
// (`kel(a, b, c)`: the loss at node (i + a, j + b, k + c))
KOKKOS_INLINE_FUNCTION Real ke_fix_share(const Field3& kel, int i, int j, int k, Real m, Real w) {
  return ke_fix_share_of([&](int a, int b, int c) { return kel(i + a, j + b, k + c); }, m, w);
}

// A node's kinetic-energy loss L as kel stores it (MomentumFinish, Hydro::expansion_impulse): L
// where L >= 0, else L per unit internal energy `content` of its 8 cells (0 where they have
// none; the quotient taken whatever the sign: a select, not a branch); and back.
KOKKOS_INLINE_FUNCTION Real ke_stored(Real loss, Real content) {
  const Real per_content = loss / content;
  return loss >= 0 ? loss : content > 0 ? per_content : Real(0);
}
KOKKOS_INLINE_FUNCTION Real ke_unstored(Real stored, Real content) {
  return stored >= 0 ? stored : stored * content;
}

// A node whose kinetic-energy discrepancy, as MomentumFinish stores it (kel: the loss L >= 0, or
// L per unit internal energy of its 8 cells where the remap made kinetic energy), says it made
// more than 1/16 of its cells' internal energy: its dual faces are redone with donor values
// (remap.cpp, Hydro::remap_step). At 1/16 a node, no cell of 8 such nodes pays more than half
// its own energy in a sweep, so ke_fix_floor does not bind.
inline constexpr Real kKeRedo = Real(1) / 16;
KOKKOS_INLINE_FUNCTION bool ke_redo(Real kel) {
  return kel < -kKeRedo;
}

// Energy the KE fix's floor left unpaid (a column's or a cell's) into the rank's sum, State::
// ke_unpaid (one atomic per column or cell, and only where the floor bound: nearly never).
KOKKOS_INLINE_FUNCTION void add_unpaid(const Kokkos::View<double, MemSpace>& unpaid, Real u) {
  if (u > 0) Kokkos::atomic_add(&unpaid(), double(u));
}

// Sum of a node field over the 8 corners of cell (i, j, k), x fastest.
template <class F3>
KOKKOS_INLINE_FUNCTION Real corner_sum(const F3& f, int i, int j, int k) {
  Real sum = 0;
  for (int c = 0; c < 2; ++c)
    for (int b = 0; b < 2; ++b)
      for (int a = 0; a < 2; ++a) sum += f(i + a, j + b, k + c);
  return sum;
}

}  // namespace mp::hydro
