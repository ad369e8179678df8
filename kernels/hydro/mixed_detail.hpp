// Helpers of the multi-material remap shared by its face fluxes (mixed_remap_faces.cpp) and
// its cell update (mixed_remap_cells.cpp); private to kernels/hydro.
#pragma once
#include "hydro/hydro.hpp"

namespace mp::hydro::mixed_detail {

// A donor cell's content (fractions, densities, energies per material): mat::read_cell on
// either layout; returns the count of the materials present.
KOKKOS_INLINE_FUNCTION int read_donor(const mat::DenseDev& d, const Field3&, const Field3&, int i,
                                      int j, int k, Real* a, Real* r, Real* e) {
  return mat::read_cell(d, i, j, k, a, r, e);
}
KOKKOS_INLINE_FUNCTION int read_donor(const mat::CompactDev& d, const Field3& rho, const Field3& en,
                                      int i, int j, int k, Real* a, Real* r, Real* e) {
  return mat::read_cell(d, rho, en, i, j, k, a, r, e);
}

// The fields of sweep d that a FaceFluxes or a RemapSource reads (s: the hydro state).
template <class T, class Dev, class State>
void set_sweep_fields(T& t, const Dev& dev, const State& s, int d, int nmat) {
  t.dev = dev;
  t.rho = s.rho;
  t.e = s.e;
  t.pre = s.pre_vol;
  t.vf = s.vol_flux[d];
  t.mf = s.mass_flux[d];
  t.ef = s.energy_flux[d];
  t.nmat = nmat;
}

}  // namespace mp::hydro::mixed_detail
