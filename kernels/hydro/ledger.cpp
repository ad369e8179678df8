// The boundary mass ledger (output.mass_ledger; docs/running.md, "Mass ledger"): after a
// sweep's face fluxes, the mass each material takes out through each face of the mesh's
// physical boundary. An Eulerian mesh changes a material's mass only there, so the ledger and
// the change of the materials' masses agree to round-off (tests/test_output.cpp checks it).
#include "core/reduce.hpp"
#include "hydro/hydro.hpp"

namespace mp::hydro {

using mat::kMaxMaterials;

namespace {

// The mass flux of each material through the face (i, j, k) normal to d, read from the
// layout's face fluxes (the face total for a compact pure donor).
KOKKOS_INLINE_FUNCTION void face_masses(const mat::CompactDev& dev, const Field3& vf,
                                        const Field3& mf, int d, int i, int j, int k,
                                        SumN<kMaxMaterials>& acc) {
  const Real f = vf(i, j, k);
  const int up = f > 0 ? 1 : 0;  // the donor is the cell below the face when f > 0
  const int di = i - up * (d == 0), dj = j - up * (d == 1), dk = k - up * (d == 2);
  const int m0 = dev.mat(di, dj, dk);
  if (m0 >= 0) {
    acc.v[m0] += double(mf(i, j, k));
    return;
  }
  const int q0 = dev.first(di, dj, dk), n = dev.nm(di, dj, dk);
  for (int q = q0; q < q0 + n; ++q) acc.v[dev.smat(q)] += double(dev.sfm[up](q));
}

KOKKOS_INLINE_FUNCTION void face_masses(const mat::DenseDev& dev, const Field3&, const Field3&, int,
                                        int i, int j, int k, SumN<kMaxMaterials>& acc) {
  for (int m = 0; m < dev.nmat; ++m) acc.v[m] += double(dev.fm(m, i, j, k));
}

// A single-material scene: the face's mass flux.
KOKKOS_INLINE_FUNCTION void face_masses(const Hydro::NoLayout&, const Field3&, const Field3& mf,
                                        int, int i, int j, int k, SumN<kMaxMaterials>& acc) {
  acc.v[0] += double(mf(i, j, k));
}

// The reduction's body over one boundary face plane (a functor: nvcc refuses an extended
// lambda whose first capture of a variable is inside `if constexpr`).
template <class Dev>
struct LedgerFaces {
  Dev dev;
  Field3 vf, mf;
  int d;
  KOKKOS_INLINE_FUNCTION void operator()(int i, int j, int k, SumN<kMaxMaterials>& acc) const {
    face_masses(dev, vf, mf, d, i, j, k, acc);
  }
};

}  // namespace

template <class Dev>
void Hydro::ledger_faces(const Dev& dev, int d) {
  const int ng = Mesh::ng;
  const auto fr = mesh_.range(Centering::Node, Region::Owned, d);
  const Field3 vf = s_.vol_flux[d], mf = s_.mass_flux[d];
  const int nm = mm_ ? mats_.n : 1;
  for (int side = 0; side < 2; ++side) {
    if (!mesh_.physical_boundary(d, side) || mesh_.boundary(d, side) == BoundaryKind::Periodic)
      continue;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = ng;
      hi[a] = ng + mesh_.owned_cells(a);
    }
    lo[d] = side == 0 ? fr[0] : fr[1] - 1;
    hi[d] = lo[d] + 1;
    SumN<kMaxMaterials> sum;
    Kokkos::parallel_reduce(
        "remap::mass_ledger", Policy3({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}),
        LedgerFaces<Dev>{dev, vf, mf, d}, Kokkos::Sum<SumN<kMaxMaterials>>(sum));
    // out of the mesh: against the axis at the low face, along it at the high one
    const double out = side == 0 ? -1.0 : 1.0;
    for (int m = 0; m < nm; ++m) ledger_[m * 6 + 2 * d + side] += out * sum.v[m];
  }
}

void Hydro::ledger_sweep(int d) {
  if (ledger_.empty()) return;
  if (!mm_)
    ledger_faces(NoLayout{}, d);
  else if (mm_->kind() == mat::LayoutKind::Dense)
    ledger_faces(mm_->dense(), d);
  else
    ledger_faces(mm_->compact(), d);
}

void Hydro::set_mass_ledger(bool on) {
  ledger_.assign(on ? std::size_t(mm_ ? mats_.n : 1) * 6 : 0, 0.0);
}

void Hydro::restore_mass_ledger(const std::vector<double>& global) {
  if (ledger_.empty()) return;
  if (global.size() != ledger_.size())
    throw RunError("the checkpoint's mass ledger has " + std::to_string(global.size()) +
                   " entries; this scene's has " + std::to_string(ledger_.size()));
  const bool root = mesh_.rank() == 0;
  for (std::size_t n = 0; n < ledger_.size(); ++n) ledger_[n] = root ? global[n] : 0.0;
}

std::vector<double> Hydro::mass_ledger() const {
  std::vector<double> global(ledger_.size(), 0.0);
  if (!ledger_.empty())
    MPI_Allreduce(ledger_.data(), global.data(), int(ledger_.size()), MPI_DOUBLE, MPI_SUM,
                  mesh_.comm());
  return global;
}

template void Hydro::ledger_faces(const Hydro::NoLayout&, int);
template void Hydro::ledger_faces(const mat::DenseDev&, int);
template void Hydro::ledger_faces(const mat::CompactDev&, int);

}  // namespace mp::hydro
