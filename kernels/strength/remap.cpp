// The strength module's remap of the stress sets (dense: per unit mass with the cell fields;
// compact: gathered from the pool, remapped, scattered) and the pooled sets' halo.
#include "strength/module.hpp"

#include "core/error.hpp"

#include "remap/per_mass.hpp"
#include "materials/rebuild.hpp"
#include "strength/halo_parity.hpp"

namespace mp::strength {

void Strength::remap(int q, const std::array<bool, 3>& axes, const std::array<Field3, 3>& mass_flux,
                     const Field3& rho, const Field3& pre, int order) {
  // the values before the step go to the set's half-step deviator (free between the corrector
  // and the next predictor, which writes it before anything reads it) and the scratch
  const StressSet& st = sets_[q];
  mp::remap::remap_per_mass(mesh_, axes, mass_flux, rho, pre,
                        {st.s[0], st.s[1], st.s[2], st.s[3], st.s[4], st.s[5], st.eps_p},
                        {st.s_half[0], st.s_half[1], st.s_half[2], st.s_half[3], st.s_half[4],
                         st.s_half[5], scratch_},
                        order);
}

// ------------------------------------------------------------------------------------------
// Pooled sets (module.hpp, "Storage").

namespace {

// Gather / scatter targets as a kernel reads them: each one's cell field, the pure-cell array
// and slot buffer of its component, its set's material.
struct PoolTargets {
  Field3 f[16], pure[16];
  Buffer slot[16];
  int mid[16];
  int n = 0;
};

// Set q's gathered components c = 0, 1, ... (stored component-major: c * n + q).
struct SetOlds {
  const Field3* old;
  int q, n;
  KOKKOS_INLINE_FUNCTION const Field3& operator[](int c) const { return old[c * n + q]; }
};

// The pooled sets' remap of one batch of NX components (Strength::remap_compact): the values
// before the step (gathered, component-major), each set's carrier mass flux and density, and
// where the new values go (the batch's pure-cell arrays and slot extras of the current pool).
// (The gather fields number max(7, sets) + 1, at most kMaxMaterials + 1.)
struct PoolRemap {
  Field3 old[mat::kMaxMaterials + 1];
  Field3 flux[mat::kMaxMaterials], rho[mat::kMaxMaterials];
  Field3 pure[7];
  Buffer slot[7];
  int mid[mat::kMaxMaterials];
};

// (Axis: the split sweep's axis at compile time, per_mass_update; pooled sets are remapped in
// split sweeps only.)
template <int NX, int Axis>
void remap_pool(const Mesh& mesh, const PoolRemap& t, const mat::CompactDev& dev, int n, Real ax,
                Real ay, Real az, const Field3& pre, int order) {
  Kokkos::parallel_for(
      "strength::remap", mesh.cells(Region::Owned), KOKKOS_LAMBDA(int i, int j, int k) {
        const int id = dev.mat(i, j, k);
        for (int q = 0; q < n; ++q) {
          // where set q's material is now: its pure cell (-2), its slot, or absent (-1)
          int at = -1;
          if (id >= 0) {
            if (id == t.mid[q]) at = -2;
          } else {
            const int f = dev.first(i, j, k), m = dev.nm(i, j, k);
            for (int s = f; s < f + m; ++s)
              if (dev.smat(s) == t.mid[q]) at = s;
          }
          if (at == -1) continue;
          const SetOlds old{t.old, q, n};
          Real out[NX];
          mp::remap::per_mass_update<NX, Axis>(i, j, k, ax, ay, az, t.flux[q], t.flux[q], t.flux[q],
                                           t.rho[q], pre, old, order, out);
          for (int c = 0; c < NX; ++c) {
            if (at == -2)
              t.pure[c](i, j, k) = out[c];
            else
              t.slot[c](at) = out[c];
          }
        }
      });
}

PoolTargets pool_targets(const mat::CompactDev& dev, const std::vector<Strength::Target>& targets,
                         const std::array<Field3, 7>& pure, const std::vector<StressSet>& sets) {
  if (targets.size() > 16) throw RunError("strength: more than 16 gather targets at once");
  PoolTargets t;
  for (const Strength::Target& g : targets) {
    t.f[t.n] = g.field;
    t.pure[t.n] = pure[g.x];
    t.slot[t.n] = dev.sx[g.x];
    t.mid[t.n++] = sets[g.q].material;
  }
  return t;
}

}  // namespace

template <class F>
void Strength::for_where(const std::string& name, Where w, F f) const {
  const int ng = Mesh::ng;
  const int ex = mesh_.extent(Centering::Cell, 0), ey = mesh_.extent(Centering::Cell, 1),
            ez = mesh_.extent(Centering::Cell, 2);
  const int ox = mesh_.owned_cells(0), oy = mesh_.owned_cells(1), oz = mesh_.owned_cells(2);
  // an owned box too thin to have an interior is its own shell
  if (w == Where::OwnedShell && (ox <= 2 * ng || oy <= 2 * ng || oz <= 2 * ng)) w = Where::Owned;
  using Range = Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long>>;
  switch (w) {
    case Where::Block:
      Kokkos::parallel_for(name, mesh_.cells(Region::All), f);
      return;
    case Where::Owned:
      Kokkos::parallel_for(name, mesh_.cells(Region::Owned), f);
      return;
    case Where::SweepX:
    case Where::SweepY:
    case Where::SweepZ: {
      const int d = w == Where::SweepX ? 0 : w == Where::SweepY ? 1 : 2;
      const auto end = mesh_.owned_end();
      int lo[3] = {ng, ng, ng}, hi[3] = {end[0], end[1], end[2]};
      lo[d] = 0;
      hi[d] = mesh_.extent(Centering::Cell, d);
      Kokkos::parallel_for(name, Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}), f);
      return;
    }
    case Where::GhostShell:
    case Where::OwnedShell: {
      // the ng-thick shell of the block (offset 0) or of the owned box (offset ng)
      const bool ghosts = w == Where::GhostShell;
      const int bx = ghosts ? ex : ox, by = ghosts ? ey : oy, bz = ghosts ? ez : oz;
      const int o = ghosts ? 0 : ng;
      Kokkos::parallel_for(
          name, Range(0, mat::shell_cells(bx, by, bz, ng)), KOKKOS_LAMBDA(long r) {
            int i, j, k;
            mat::shell_cell(r, bx, by, bz, ng, i, j, k);
            f(i + o, j + o, k + o);
          });
      return;
    }
  }
}

void Strength::gather(const mat::CompactDev& dev, const std::vector<Target>& targets,
                      Where w) const {
  const PoolTargets t = pool_targets(dev, targets, pure_, sets_);
  for_where(
      "strength::gather", w, KOKKOS_LAMBDA(int i, int j, int k) {
        const int id = dev.mat(i, j, k);
        if (id >= 0) {
          for (int g = 0; g < t.n; ++g)
            t.f[g](i, j, k) = t.mid[g] == id ? t.pure[g](i, j, k) : Real(0);
          return;
        }
        const int f = dev.first(i, j, k), n = dev.nm(i, j, k);
        for (int g = 0; g < t.n; ++g) {
          Real v = 0;
          for (int s = f; s < f + n; ++s)
            if (dev.smat(s) == t.mid[g]) v = t.slot[g](s);
          t.f[g](i, j, k) = v;
        }
      });
}

void Strength::scatter(const std::vector<Target>& targets, Where w) const {
  const mat::CompactDev dev = mm_->compact();
  const PoolTargets t = pool_targets(dev, targets, pure_, sets_);
  for_where(
      "strength::scatter", w, KOKKOS_LAMBDA(int i, int j, int k) {
        const int id = dev.mat(i, j, k);
        if (id >= 0) {
          for (int g = 0; g < t.n; ++g)
            if (id == t.mid[g]) t.pure[g](i, j, k) = t.f[g](i, j, k);
          return;
        }
        const int f = dev.first(i, j, k), n = dev.nm(i, j, k);
        for (int g = 0; g < t.n; ++g)
          for (int s = f; s < f + n; ++s)
            if (dev.smat(s) == t.mid[g]) t.slot[g](s) = t.f[g](i, j, k);
      });
}

void Strength::remap(const std::vector<hydro::Carrier>& mine, const std::array<bool, 3>& axes,
                     const Field3& pre, int order) {
  if (pooled_) return;  // (remap_materials)
  for (int q = 0; q < sets(); ++q) remap(q, axes, mine[q].flux, mine[q].rho, pre, order);
}

void Strength::remap_materials(const std::vector<hydro::Carrier>& mine,
                               const std::array<bool, 3>& axes, const Field3& pre, int order) {
  // pooled stress sets: from the pool before the update into the pool after it (one axis per
  // step: MaterialState::previous is the pool before this sweep's update)
  if (!pooled_) return;
  if (int(axes[0]) + int(axes[1]) + int(axes[2]) != 1)
    throw RunError("pooled stress sets need split remap sweeps");
  std::vector<Field3> flux, crho;
  for (int q = 0; q < sets(); ++q) {
    flux.push_back(mine[q].flux[0]);
    crho.push_back(mine[q].rho);
  }
  remap_compact(axes, flux, crho, pre, order);
}

void Strength::remap_compact(const std::array<bool, 3>& axes, const std::vector<Field3>& flux,
                             const std::vector<Field3>& rho, const Field3& pre, int order) {
  // The sets' values before the update are gathered into the gather fields (the owned cells
  // and the two layers of ghosts the fluxes along the sweep read), as many components of every
  // set at once as the fields hold (all 7 with one set, 4 with two); then one launch remaps
  // them all and writes each new value into the updated pool (the cells that hold the set's
  // material), with each face's donor and Courant number found once per set for all its
  // components. A pure cell's arrays are shared by the sets, so every set's component is read
  // (gathered) before any is written. (Reading the pool inside the remap instead of gathering
  // took 13 ms a cycle against 5 + 4 for the stripes of the layout study, a branch per read.
  // A remap launch and a scatter launch per component and set, 14 + 14 a sweep with two sets,
  // took 2.7 times as long on the zone-0.05 perforator: docs/perforator.md, "Cycle cost".)
  std::vector<Field3> g(cell_half_.begin(), cell_half_.end());
  g.insert(g.end(), gather_.begin(), gather_.end());
  g.push_back(scratch_);
  const int n = sets();
  const int batch = std::max(1, std::min(7, int(g.size()) / n));
  const Where w = axes[0] ? Where::SweepX : axes[1] ? Where::SweepY : Where::SweepZ;
  const Real ax = axes[0] ? 1 : 0, ay = axes[1] ? 1 : 0, az = axes[2] ? 1 : 0;
  for (int x0 = 0; x0 < 7; x0 += batch) {
    const int x1 = std::min(7, x0 + batch), nx = x1 - x0;
    std::vector<Target> before;
    for (int x = x0; x < x1; ++x)
      for (int q = 0; q < n; ++q) before.push_back({q, x, g[std::size_t((x - x0) * n + q)]});
    gather(mm_->previous(), before, w);
    const mat::CompactDev dev = mm_->compact();
    PoolRemap t;
    for (int q = 0; q < n; ++q) {
      t.flux[q] = flux[std::size_t(q)];
      t.rho[q] = rho[std::size_t(q)];
      t.mid[q] = sets_[std::size_t(q)].material;
    }
    if (before.size() > std::size(t.old))
      throw RunError("strength: more gather fields than a remap takes");
    for (const Target& b : before) t.old[(b.x - x0) * n + b.q] = b.field;
    for (int x = x0; x < x1; ++x) {
      t.pure[x - x0] = pure_[std::size_t(x)];
      t.slot[x - x0] = dev.sx[x];
    }
    using Launch = void (*)(const Mesh&, const PoolRemap&, const mat::CompactDev&, int, Real, Real,
                            Real, const Field3&, int);
    static constexpr Launch launch[3][7] = {
        {remap_pool<1, 0>, remap_pool<2, 0>, remap_pool<3, 0>, remap_pool<4, 0>, remap_pool<5, 0>,
         remap_pool<6, 0>, remap_pool<7, 0>},
        {remap_pool<1, 1>, remap_pool<2, 1>, remap_pool<3, 1>, remap_pool<4, 1>, remap_pool<5, 1>,
         remap_pool<6, 1>, remap_pool<7, 1>},
        {remap_pool<1, 2>, remap_pool<2, 2>, remap_pool<3, 2>, remap_pool<4, 2>, remap_pool<5, 2>,
         remap_pool<6, 2>, remap_pool<7, 2>}};
    launch[axes[0] ? 0 : axes[1] ? 1 : 2][nx - 1](mesh_, t, dev, n, ax, ay, az, pre, order);
  }
}

void Strength::exchange_compact(Halo& halo) {
  std::vector<Field3> f(cell_half_.begin(), cell_half_.end());
  f.push_back(scratch_);
  for (int q = 0; q < sets(); ++q) {
    std::vector<HaloField> h;
    std::vector<Target> t;
    for (int x = 0; x < 7; ++x) {
      t.push_back({q, x, f[x]});
      h.push_back({f[x], Centering::Cell, {kParity[x][0], kParity[x][1], kParity[x][2]}});
    }
    gather(mm_->compact(), t, Where::OwnedShell);
    halo.exchange(h);
    scatter(t, Where::GhostShell);
  }
}

}  // namespace mp::strength
