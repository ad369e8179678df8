// Remap of per-mass cell quantities (per_mass.hpp).
#include "hydro/per_mass.hpp"

#include "core/math.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

void remap_per_mass(const Mesh& mesh, const std::array<bool, 3>& axes,
                    const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
                    const std::vector<Field3>& fields, const Field3& scratch, int order) {
  for (const Field3& phi : fields) {
    Kokkos::deep_copy(scratch, phi);
    remap_per_mass_from(mesh, axes, mass_flux, rho, pre, scratch, phi, order);
  }
}

void remap_per_mass_from(const Mesh& mesh, const std::array<bool, 3>& axes,
                         const std::array<Field3, 3>& mass_flux, const Field3& rho,
                         const Field3& pre, const Field3& old, const Field3& phi, int order) {
  const Real ax = axes[0] ? 1 : 0, ay = axes[1] ? 1 : 0, az = axes[2] ? 1 : 0;
  auto mfx = mass_flux[0], mfy = mass_flux[1], mfz = mass_flux[2];
  {
    Kokkos::parallel_for(
        "remap::per_mass", mesh.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
          // flux of phi through face (fi, fj, fk) normal to d with mass flux m, from its donor
          auto flux = [&](const Field3& mf, int fi, int fj, int fk, int d) {
            const Real m = mf(fi, fj, fk);
            if (m == 0) return Real(0);  // (a carrier absent from the donor)
            const int sx = d == 0, sy = d == 1, sz = d == 2;
            const int dn = m > 0 ? -1 : 0, st = m > 0 ? 1 : -1;
            const int di = fi + dn * sx, dj = fj + dn * sy, dk = fk + dn * sz;
            const Real sm = mabs(m) / (rho(di, dj, dk) * pre(di, dj, dk));
            return m * face_value(old(di - st * sx, dj - st * sy, dk - st * sz), old(di, dj, dk),
                                  old(di + st * sx, dj + st * sy, dk + st * sz), sm, order);
          };
          const Real m0 = rho(i, j, k) * pre(i, j, k);
          // the same sums, in the same order, as the hydro's cell update
          Real dm = 0, dq = 0;
          if (ax > 0) {
            dm += mfx(i, j, k) - mfx(i + 1, j, k);
            dq += flux(mfx, i, j, k, 0) - flux(mfx, i + 1, j, k, 0);
          }
          if (ay > 0) {
            dm += mfy(i, j, k) - mfy(i, j + 1, k);
            dq += flux(mfy, i, j, k, 1) - flux(mfy, i, j + 1, k, 1);
          }
          if (az > 0) {
            dm += mfz(i, j, k) - mfz(i, j, k + 1);
            dq += flux(mfz, i, j, k, 2) - flux(mfz, i, j, k + 1, 2);
          }
          // a cell its carrier left holds 0 (multi-material carriers; hydro.hpp)
          const Real m1 = m0 + dm;
          phi(i, j, k) = m1 > 0 ? (old(i, j, k) * m0 + dq) / m1 : Real(0);
        });
  }
}

}  // namespace mp::hydro
