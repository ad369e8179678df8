// Noh's artificial heat flux (numerics.heat_flux; docs/numerics.md "Artificial heat flux").
//
// W. F. Noh, "Errors for calculations of strong shocks using an artificial viscosity and an
// artificial heat flux", J. Comput. Phys. 72:78-120 (1987): a shock captured by a viscosity
// leaves the gas it shocked first (at a wall, at the origin of a converging shock, at a
// shock's birth on a few cells of radius) with too much entropy, and a conduction of internal
// energy acting where the viscosity acts, H = h rho dx |du| grad e, lets that heat leave.
//
// Here: before the Lagrangian step, between each pair of face neighbours that the viscosity
// compresses in a converging flow (both cells; point.hpp, `converging`: the strain rate's
// middle eigenvalue compresses too, as in the shock of an implosion, and not in a planar or a
// diverging shock, which this flux only broadens: Sedov's shock +1.2 % of its radius with it
// everywhere), internal energy flows down the gradient of the specific energy with the
// conductance h min(rho) min(J) A (J a cell's compressive velocity jump, recovered from its
// q = rho (c_Q J^2 + c_L c J) in the viscosity's launch, A the face's area). "Both": no flux
// into gas that does not converge (a converging inflow with a q of its own, Noh's, does take
// some; docs). What one cell gives its neighbour takes: the sum is conserved to round-off. Explicit
// sub-steps, each at most the step at which every cell's new energy is a convex combination of its
// own and its neighbours' (the maximum principle: no energy goes negative or beyond its
// neighbours'); the conductance is frozen over the step (rho, q, c of the step's start). No launch
// at all in a cycle without a converging cell. Single-material scenes (a mixed cell's per-material
// energies have no such conduction; docs).
#include <mpi.h>

#include <cmath>

#include "core/columns.hpp"
#include "core/math.hpp"
#include "hydro/hydro.hpp"
#include "hydro/point.hpp"

namespace mp::hydro {

namespace {

// The conduction's region and rate over a rank: the largest rate sum_f kappa_f / m of a cell
// (1 / time) and the box of cells that conduct (lo > hi: none).
struct Reach {
  Real rate;
  int lo[3], hi[3];
};

// The face conductance per unit h: min(rho) min(J) A (0 where either cell does not converge).
struct Conductance {
  Field3 rho, J;
  Real ax, ay, az;
  template <class F>
  KOKKOS_INLINE_FUNCTION void faces(int i, int j, int k, const F& f) const {
    const Real ja = J(i, j, k), ra = rho(i, j, k);
    const auto face = [&](int ib, int jb, int kb, Real a) {
      const Real jf = mmin(ja, J(ib, jb, kb));
      if (jf > 0) f(ib, jb, kb, mmin(ra, rho(ib, jb, kb)) * jf * a);
    };
    face(i - 1, j, k, ax);
    face(i + 1, j, k, ax);
    face(i, j - 1, k, ay);
    face(i, j + 1, k, ay);
    face(i, j, k - 1, az);
    face(i, j, k + 1, az);
  }
};

// parallel_reduce functor: each conducting cell's rate h sum_f kappa_f / (rho V) and place
struct ReachOf {
  using value_type = Reach;
  Conductance kc;
  Real h, vol;
  Kokkos::View<int, MemSpace> flag;
  int first;  // the first owned cell index (lowers the flag there)
  KOKKOS_INLINE_FUNCTION void init(Reach& r) const {
    r.rate = 0;
    for (int d = 0; d < 3; ++d) {
      r.lo[d] = 1 << 30;
      r.hi[d] = -1;
    }
  }
  template <class R, class O>
  static KOKKOS_INLINE_FUNCTION void merge(R& r, const O& o) {
    if (o.rate > r.rate) r.rate = o.rate;
    for (int d = 0; d < 3; ++d) {
      if (o.lo[d] < r.lo[d]) r.lo[d] = o.lo[d];
      if (o.hi[d] > r.hi[d]) r.hi[d] = o.hi[d];
    }
  }
  // (Kokkos 3 joins volatile values, Kokkos 4 refuses a volatile join)
#if KOKKOS_VERSION >= 30700
  KOKKOS_INLINE_FUNCTION void join(Reach& r, const Reach& o) const {
    merge(r, o);
  }
#else
  KOKKOS_INLINE_FUNCTION void join(volatile Reach& r, const volatile Reach& o) const {
    merge(r, o);
  }
#endif
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, Reach& r) const {
    if (i == first && j == first && k == first) flag() = 0;
    if (!(kc.J(i, j, k) > 0)) return;
    Real sum = 0;
    kc.faces(i, j, k, [&](int, int, int, Real kappa) { sum += kappa; });
    if (!(sum > 0)) return;
    const Real rate = h * sum / (kc.rho(i, j, k) * vol);
    if (rate > r.rate) r.rate = rate;
    const int at[3] = {i, j, k};
    for (int d = 0; d < 3; ++d) {
      if (at[d] < r.lo[d]) r.lo[d] = at[d];
      if (at[d] > r.hi[d]) r.hi[d] = at[d];
    }
  }
};

}  // namespace

int Hydro::heat_flux(Real dt) {
  if (!conducts()) return 0;
  // any converging cell on any rank (the flag the viscosity launch raised; read without a
  // launch, lowered by the launch below, which runs only when it is up)
  int mine = 0, any = 0;
  Kokkos::deep_copy(mine, s_.converging);
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, mesh_.comm());
  if (!any) return 0;
  const Real h = opt_.heat_flux;
  const Geometry g = mesh_.geometry();
  const Real vol = g.cell_volume();
  auto rho = s_.rho, e = s_.e, J = s_.cjump;
  const Conductance kf{rho, J, g.dx[1] * g.dx[2], g.dx[0] * g.dx[2], g.dx[0] * g.dx[1]};
  // the neighbours' jumps: the owners' (a ghost's q is found from its own stencil)
  halo_.exchange({{J, Centering::Cell, {1, 1, 1}}});
  // the largest rate and the box of the cells that conduct (their faces reach one further)
  Reach reach;
  Kokkos::parallel_reduce("conduction::reach", mesh_.cells(Region::Owned),
                          ReachOf{kf, h, vol, s_.converging, Mesh::ng}, reach);
  double rate = double(reach.rate), global = 0;
  MPI_Allreduce(&rate, &global, 1, MPI_DOUBLE, MPI_MAX, mesh_.comm());
  if (!(global > 0)) return 0;
  // sub-steps: each within every cell's convex-combination bound ds * rate <= 1
  const int n = int(std::ceil(double(dt) * global * (1 + 1e-6)));
  const Real ds = dt / Real(n);
  // scratch for the energy changes: the remap's first pre-volumes (written by the corrector
  // before the remap reads them)
  auto de = s_.pre_vol;
  const bool here = reach.hi[0] >= reach.lo[0];
  // The faces' conductances, frozen over the step: found once here, not in every sub-step.
  // kx(i, j, k) holds the face between cells (i - 1, j, k) and (i, j, k) (a node-extent
  // scratch of the remap, as ky and kz), Conductance's value or 0 where it has none; the
  // box's cells read their low faces and the high ones of the box's last cells, so the launch
  // runs over the box and one cell beyond its high sides (owned or ghost cells: the box is
  // owned; a face found from its high cell has the value its low cell found: the min of two
  // positive values is symmetric). A face without conductance adds kappa (e_b - e_a) = +-0 to
  // the flux's sum, which never holds -0 (it starts at +0, and a sum of nonzero terms that
  // cancels is +0): the sum, so the energies, are the per-face test's bit for bit.
  auto kx = s_.dual_u, ky = s_.dual_v, kz = s_.dual_w;
  const Real c = h * ds / vol;
  if (here) {
    const int clo[3] = {reach.lo[0], reach.lo[1], reach.lo[2]};
    const int chi[3] = {reach.hi[0] + 2, reach.hi[1] + 2, reach.hi[2] + 2};
    const Real fax = kf.ax, fay = kf.ay, faz = kf.az;
    for_columns(
        "conduction::conductance", clo, chi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
          const auto Ja = local(J), ra = local(rho), X = local(kx), Y = local(ky), Z = local(kz);
          const auto face = [&](int ia, int ja, int ka, int ib, int jb, int kb, Real a) {
            const Real jf = mmin(Ja(ia, ja, ka), Ja(ib, jb, kb));
            return jf > 0 ? mmin(ra(ia, ja, ka), ra(ib, jb, kb)) * jf * a : Real(0);
          };
#pragma GCC ivdep
          for (int k = k0; k < k1; ++k) {
            X(i, j, k) = face(i, j, k, i - 1, j, k, fax);
            Y(i, j, k) = face(i, j, k, i, j - 1, k, fay);
            Z(i, j, k) = face(i, j, k, i, j, k - 1, faz);
          }
        });
  }
  for (int s = 0; s < n; ++s) {
    if (here) {
      const int blo[3] = {reach.lo[0], reach.lo[1], reach.lo[2]};
      const int bhi[3] = {reach.hi[0] + 1, reach.hi[1] + 1, reach.hi[2] + 1};
      for_columns(
          "conduction::flux", blo, bhi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
            const auto ea = local(e), ra = local(rho), da = local(de), X = local(kx), Y = local(ky),
                       Z = local(kz);
#pragma GCC ivdep
            for (int k = k0; k < k1; ++k) {
              const Real e0 = ea(i, j, k);
              // (the faces in Conductance::faces's order)
              Real sum = 0;
              sum += X(i, j, k) * (ea(i - 1, j, k) - e0);
              sum += X(i + 1, j, k) * (ea(i + 1, j, k) - e0);
              sum += Y(i, j, k) * (ea(i, j - 1, k) - e0);
              sum += Y(i, j + 1, k) * (ea(i, j + 1, k) - e0);
              sum += Z(i, j, k) * (ea(i, j, k - 1) - e0);
              sum += Z(i, j, k + 1) * (ea(i, j, k + 1) - e0);
              da(i, j, k) = c * sum / ra(i, j, k);
            }
          });
      for_columns(
          "conduction::apply", blo, bhi, KOKKOS_LAMBDA(int i, int j, int k0, int k1) {
            const auto ea = local(e), da = local(de);
#pragma GCC ivdep
            for (int k = k0; k < k1; ++k) ea(i, j, k) += da(i, j, k);
          });
    }
    halo_.exchange({{e, Centering::Cell, {1, 1, 1}}});
  }
  return n;
}

}  // namespace mp::hydro
