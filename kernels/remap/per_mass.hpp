// Cell quantities carried per unit mass through the remap (DESIGN.md §4.1, "material scalars"
// of single-material scenes): the strength module's deviator and plastic strain, the burn
// module's burn fraction. One path for all of them, the internal energy's: van Leer face values
// time-centred by the donor's mass Courant number, with the cell mass fluxes of the step.
// All the quantities of one carrier go in one launch: the faces' donors and Courant numbers
// are found once per face and serve every quantity (per_mass_update).
#pragma once
#include <array>
#include <vector>

#include "core/math.hpp"
#include "remap/advect.hpp"
#include "mesh/mesh.hpp"

namespace mp::remap {

// The most quantities one launch carries (the strength module's 7).
inline constexpr int kPerMassMax = 7;

// The donor of the face (fi, fj, fk) normal to d with mass flux m, and its mass Courant number.
struct PerMassFace {
  Real m, sm;
  int di, dj, dk, st;
};

KOKKOS_INLINE_FUNCTION PerMassFace per_mass_face(const Field3& mf, const Field3& rho,
                                                 const Field3& pre, int fi, int fj, int fk, int d) {
  PerMassFace f;
  f.m = mf(fi, fj, fk);
  f.sm = 0;
  f.di = fi, f.dj = fj, f.dk = fk, f.st = 0;
  if (f.m == 0) return f;  // (a carrier absent from the donor)
  const int sx = d == 0, sy = d == 1, sz = d == 2;
  const int dn = f.m > 0 ? -1 : 0;
  f.st = f.m > 0 ? 1 : -1;
  f.di = fi + dn * sx, f.dj = fj + dn * sy, f.dk = fk + dn * sz;
  f.sm = mabs(f.m) / (rho(f.di, f.dj, f.dk) * pre(f.di, f.dj, f.dk));
  return f;
}

// The flux of the quantity `old` through a face: mass flux times the limited face value.
KOKKOS_INLINE_FUNCTION Real per_mass_flux(const PerMassFace& f, const Field3& old, int d,
                                          int order) {
  if (f.m == 0) return Real(0);
  const int sx = d == 0, sy = d == 1, sz = d == 2;
  const int st = f.st;
  return f.m * face_value(old(f.di - st * sx, f.dj - st * sy, f.dk - st * sz),
                          old(f.di, f.dj, f.dk),
                          old(f.di + st * sx, f.dj + st * sy, f.dk + st * sz), f.sm, order);
}

// One cell's new values of the N quantities `old[0..N)` after the step over the faces normal
// to the axes whose ax, ay, az are positive (mfx, mfy, mfz their mass fluxes): the same sums, in
// the same order, as the hydro's cell update. A cell its carrier left holds 0 (multi-material
// carriers; hydro.hpp). (N is a template parameter so that the sums stay in registers: with a
// run-time count the burn fraction's single field took twice as long.) A split sweep may name
// its axis at compile time (Axis 0, 1 or 2; ax, ay, az then unread): the index steps along it
// are constants, as in the hydro's sweep kernels (remap_sweep.cpp), with the same sums.
template <int N, int Axis = -1, class Olds>
KOKKOS_INLINE_FUNCTION void per_mass_update(int i, int j, int k, Real ax, Real ay, Real az,
                                            const Field3& mfx, const Field3& mfy, const Field3& mfz,
                                            const Field3& rho, const Field3& pre, const Olds& old,
                                            int order, Real (&out)[N]) {
  const Real m0 = rho(i, j, k) * pre(i, j, k);
  Real dm = 0;
  Real dq[N];
  for (int g = 0; g < N; ++g) dq[g] = 0;
  for (int d = 0; d < 3; ++d) {
    if (Axis >= 0 ? d != Axis : !((d == 0 ? ax : d == 1 ? ay : az) > 0)) continue;
    const int sx = d == 0, sy = d == 1, sz = d == 2;
    const Field3& mf = d == 0 ? mfx : d == 1 ? mfy : mfz;
    const PerMassFace lo = per_mass_face(mf, rho, pre, i, j, k, d);
    const PerMassFace hi = per_mass_face(mf, rho, pre, i + sx, j + sy, k + sz, d);
    dm += lo.m - hi.m;
    for (int g = 0; g < N; ++g)
      dq[g] += per_mass_flux(lo, old[g], d, order) - per_mass_flux(hi, old[g], d, order);
  }
  const Real m1 = m0 + dm;
  for (int g = 0; g < N; ++g) out[g] = m1 > 0 ? (old[g](i, j, k) * m0 + dq[g]) / m1 : Real(0);
}

// One remap step over the faces normal to `axes` for every field in `fields` (at most
// kPerMassMax), on the owned cells (the halo fills the ghosts after the step). `rho` and `pre`
// are the cell density and volume before the step (call before the cell update changes rho);
// `scratch` holds at least as many cell fields as `fields`, which the function overwrites
// (with the values before the step). Two launches whatever the number of fields.
void remap_per_mass(const Mesh& mesh, const std::array<bool, 3>& axes,
                    const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
                    const std::vector<Field3>& fields, const std::vector<Field3>& scratch,
                    int order);

}  // namespace mp::remap
