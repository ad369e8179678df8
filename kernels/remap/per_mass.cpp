// Remap of per-mass cell quantities (per_mass.hpp).
#include "remap/per_mass.hpp"

#include "core/axis.hpp"
#include "core/error.hpp"

namespace mp::remap {

namespace {
struct Fields {
  Field3 f[kPerMassMax];
  KOKKOS_INLINE_FUNCTION const Field3& operator[](int g) const { return f[g]; }
};

template <int N, int Axis>
void remap_axis(const Mesh& mesh, const std::array<bool, 3>& axes,
                const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
                const Fields& phi, const Fields& old, int order) {
  const Real ax = axes[0] ? 1 : 0, ay = axes[1] ? 1 : 0, az = axes[2] ? 1 : 0;
  const Field3 mfx = mass_flux[0], mfy = mass_flux[1], mfz = mass_flux[2];
  Kokkos::parallel_for(
      "remap::per_mass", mesh.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        Real out[N];
        per_mass_update<N, Axis>(i, j, k, ax, ay, az, mfx, mfy, mfz, rho, pre, old, order, out);
        for (int g = 0; g < N; ++g) phi.f[g](i, j, k) = out[g];
      });
}

// A split sweep's axis at compile time (per_mass_update), else the axes at run time.
template <int N>
void remap_n(const Mesh& mesh, const std::array<bool, 3>& axes,
             const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
             const Fields& phi, const Fields& old, int order) {
  if (int(axes[0]) + int(axes[1]) + int(axes[2]) != 1) {
    remap_axis<N, -1>(mesh, axes, mass_flux, rho, pre, phi, old, order);
    return;
  }
  with_axis(axes[0]   ? 0
            : axes[1] ? 1
                      : 2,
            [&](auto a) {
              remap_axis<N, decltype(a)::value>(mesh, axes, mass_flux, rho, pre, phi, old, order);
            });
}

}  // namespace

void remap_per_mass(const Mesh& mesh, const std::array<bool, 3>& axes,
                    const std::array<Field3, 3>& mass_flux, const Field3& rho, const Field3& pre,
                    const std::vector<Field3>& fields, const std::vector<Field3>& scratch,
                    int order) {
  const int n = int(fields.size());
  if (n == 0) return;
  if (n > kPerMassMax || scratch.size() < fields.size())
    throw RunError("remap_per_mass: too many fields, or too few scratch fields");
  Fields phi, old;
  for (int g = 0; g < n; ++g) phi.f[g] = fields[std::size_t(g)], old.f[g] = scratch[std::size_t(g)];
  // the values before the step, every cell (the fluxes read two layers of ghosts): where every
  // view is contiguous and exactly the cells' extent (the mesh's own fields), the whole span in
  // one flat range (element e is the same cell in every view); else point by point. (On a 1-D
  // run's N x 2 x 2 mesh the point-by-point copy was 7 % of the strength cycle.)
  int lo[3], hi[3];
  mesh.box(Centering::Cell, Region::All, lo, hi);
  bool flat = true;
  for (int g = 0; g < n; ++g)
    for (const Field3* f : {&phi.f[g], &old.f[g]}) {
      flat = flat && f->span_is_contiguous();
      for (int d = 0; d < 3; ++d) flat = flat && lo[d] == 0 && int(f->extent(d)) == hi[d];
    }
  if (flat)
    Kokkos::parallel_for(
        "remap::per_mass_copy",
        Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long>>(0, long(phi.f[0].span())),
        KOKKOS_LAMBDA(long e) {
          for (int g = 0; g < n; ++g) old.f[g].data()[e] = phi.f[g].data()[e];
        });
  else
    Kokkos::parallel_for(
        "remap::per_mass_copy", mesh.cells(Region::All), KOKKOS_LAMBDA(int i, int j, int k) {
          for (int g = 0; g < n; ++g) old.f[g](i, j, k) = phi.f[g](i, j, k);
        });
  using Launch = void (*)(const Mesh&, const std::array<bool, 3>&, const std::array<Field3, 3>&,
                          const Field3&, const Field3&, const Fields&, const Fields&, int);
  static constexpr Launch launch[kPerMassMax] = {remap_n<1>, remap_n<2>, remap_n<3>, remap_n<4>,
                                                 remap_n<5>, remap_n<6>, remap_n<7>};
  launch[n - 1](mesh, axes, mass_flux, rho, pre, phi, old, order);
}

}  // namespace mp::remap
