// The material halo: MaterialState::exchange fills the ghost cells' material content from the
// neighbours' messages and the boundary conditions, through one MaterialState::assign.
#include "materials/layout.hpp"

#include "materials/rebuild.hpp"
#include "mesh/halo.hpp"

namespace mp::mat {

namespace {

// The material halo fills the ghosts axis by axis (x, then y, then z), so that edge and corner
// ghosts come through the face neighbours. HaloSource<Dev> is the content of a cell after the
// first `done` sweeps, computed from the received messages without storing anything: a cell in
// a ghost slab of sweep d took its content from that sweep's message (neighbour rank), from
// its mirror / wall cell (physical boundary) or from the owned cell one block-length away (a
// periodic axis this rank holds alone: no message to itself, as the field halo's Self sides)
// as that cell stood after sweep d-1; every other cell
// kept its content. Walking back through the sweeps gives each ghost exactly the content that a
// pool rebuild after every sweep would have stored, so one update per exchange suffices (in
// place where no ghost's materials change, else one rebuild; MaterialState::assign).
template <class Dev>
struct HaloSource {
  // a ghost's content comes from owned cells (never changed here) and the messages, so ghosts
  // may be written where they are (the dense layout always does)
  static constexpr bool in_place = true;
  static constexpr bool ghosts_only = true;  // changed() holds for ghost cells only
  Dev dev;
  Field3 rho, e;  // cell arrays (compact reads pure cells from them)
  int ng, nmat, done;
  int ext[3], nl[3];
  // per sweep and side: 0 neighbour rank, 1 reflective, 2 outflow, 3 this rank (a periodic axis
  // held by one rank: the ghost is the owned cell nl layers away, with no message)
  int mode[3][2];
  // per sweep and side: the message received (the ng layers next to the face): per cell a head
  // of 3 values, then the records of the cells that are not pure, only of the materials present
  // (alpha, rho, e each, in material order). A pure cell's head is -(id + 1), rho, e; any
  // other's is (mask of the materials present, hi, lo), its records at hi * 2^20 + lo values
  // after the heads (every one of these is an integer below 2^24, exact in float too).
  Buffer recv[3][2];
  static constexpr long kSplit = 1L << 20;

  // Slab cell of sweep d (the ng layers of one side along d; k fastest, as the fields): its
  // index in the message; x is (i, j, k) with x[d] counted from the slab's first layer.
  KOKKOS_INLINE_FUNCTION long slab_cell(int d, const int x[3]) const {
    int n[3] = {ext[0], ext[1], ext[2]};
    n[d] = ng;
    return x[2] + long(n[2]) * (x[1] + long(n[1]) * x[0]);
  }
  KOKKOS_INLINE_FUNCTION long slab_cells(int d) const {
    int n[3] = {ext[0], ext[1], ext[2]};
    n[d] = ng;
    return long(n[0]) * n[1] * n[2];
  }
  // The received slab cell of sweep d, side s holding (i, j, k) = idx.
  KOKKOS_INLINE_FUNCTION long received_cell(int d, int s, const int idx[3]) const {
    int loc[3] = {idx[0], idx[1], idx[2]};
    loc[d] = s == 0 ? idx[d] : idx[d] - (ng + nl[d]);
    return slab_cell(d, loc);
  }

  // 0: low ghost slab of axis d, 1: high ghost slab, -1: owned along d.
  KOKKOS_INLINE_FUNCTION int side_of(int d, int x) const {
    if (x < ng) return 0;
    if (x >= ng + nl[d]) return 1;
    return -1;
  }
  // The cell along d whose content (after sweep d-1) ghost x of side s copies, for a side
  // without a message: the mirror across the face (reflective), the wall cell (outflow), or the
  // owned cell nl layers away (periodic on this rank; what the message to itself would carry).
  KOKKOS_INLINE_FUNCTION int source_index(int d, int s, int x) const {
    if (mode[d][s] == 1) return s == 0 ? 2 * ng - 1 - x : 2 * (ng + nl[d]) - 1 - x;
    if (mode[d][s] == 3) return s == 0 ? x + nl[d] : x - nl[d];
    return s == 0 ? ng : ng + nl[d] - 1;
  }
  KOKKOS_INLINE_FUNCTION bool changed(int i, int j, int k) const {
    const int idx[3] = {i, j, k};
    for (int d = 0; d < done; ++d)
      if (side_of(d, idx[d]) >= 0) return true;
    return false;
  }
  KOKKOS_INLINE_FUNCTION int read(int i, int j, int k, Real* a, Real* r, Real* en) const;
  // MaterialState::assign's shortcut (compact), and the pack's: true when the content is one
  // material, found without the per-material arrays (a pure stored cell or a pure cell's head
  // in a message).
  static constexpr bool has_pure = true;
  KOKKOS_INLINE_FUNCTION bool pure(int i, int j, int k, int& id, Real& r, Real& en) const {
    int idx[3] = {i, j, k}, d = 0, s = 0;
    if (source_of(idx, d, s)) {
      const long o = received_cell(d, s, idx) * 3;
      const Buffer& b = recv[d][s];
      const Real a0 = b(o);
      if (!(a0 < 0)) return false;
      id = int(-a0) - 1;
      r = b(o + 1);
      en = b(o + 2);
      return true;
    }
    return stored_pure(idx[0], idx[1], idx[2], id, r, en);
  }
  KOKKOS_INLINE_FUNCTION bool stored_pure(int i, int j, int k, int& id, Real& r, Real& en) const;
  // MaterialState::assign's ghost shell as columns (host backends; rebuild.hpp, GhostColumns):
  // after the three sweeps, a cell that took no message along x or y has its content from the
  // stored cell whose x and y are those of column (i, j) walked back through the two sweeps
  // (each sweep moves its own coordinate only), (si, sj); false where x or y took a message.
  static constexpr bool ghost_columns = true;
  KOKKOS_INLINE_FUNCTION bool source_column(int i, int j, int& si, int& sj) const {
    if (done != 3) return false;  // (every ghost of the shell changed: the final update)
    int idx[2] = {i, j};
    for (int d = 1; d >= 0; --d) {
      const int s = side_of(d, idx[d]);
      if (s < 0) continue;
      if (mode[d][s] == 0) return false;
      idx[d] = source_index(d, s, idx[d]);
    }
    si = idx[0];
    sj = idx[1];
    return true;
  }
  // ... and its z: k for an owned layer, the source layer of a z ghost that took no message,
  // -1 for one that did.
  KOKKOS_INLINE_FUNCTION int source_k(int k) const {
    const int s = side_of(2, k);
    if (s < 0) return k;
    return mode[2][s] == 0 ? -1 : source_index(2, s, k);
  }
  // Walks ghost idx back through the sweeps: true where it took a message (idx then the cell
  // in sweep d's, side s's slab), false where it copies a stored cell (idx that cell).
  KOKKOS_INLINE_FUNCTION bool source_of(int idx[3], int& d, int& s) const {
    for (d = done - 1; d >= 0; --d) {
      const int x = idx[d];
      s = side_of(d, x);
      if (s < 0) continue;  // sweep d left this cell alone
      if (mode[d][s] == 0) return true;
      // a boundary or periodic ghost copied the content its source cell had after sweep d-1
      idx[d] = source_index(d, s, x);
    }
    return false;
  }
  // The received record of slab cell idx of sweep d, side s: emit(m, alpha, rho, e) for each of
  // its materials, ascending; returns their count.
  template <class Emit>
  KOKKOS_INLINE_FUNCTION int message_record(int d, int s, const int idx[3],
                                            const Emit& emit) const {
    const long cell = received_cell(d, s, idx);
    const Buffer& b = recv[d][s];
    const Real a0 = b(cell * 3);
    if (a0 < 0) {  // a pure cell's head (pack): -(id + 1), rho, e
      emit(int(-a0) - 1, Real(1), b(cell * 3 + 1), b(cell * 3 + 2));
      return 1;
    }
    const int mask = int(a0);
    long o = 3 * slab_cells(d) + long(b(cell * 3 + 1)) * kSplit + long(b(cell * 3 + 2));
    int cnt = 0;
    for (int m = 0; (mask >> m) != 0; ++m) {
      if (!((mask >> m) & 1)) continue;
      emit(m, b(o), b(o + 1), b(o + 2));
      o += 3;
      ++cnt;
    }
    return cnt;
  }
  KOKKOS_INLINE_FUNCTION int content(int i, int j, int k, Real* a, Real* r, Real* en) const {
    int idx[3] = {i, j, k}, d = 0, s = 0;
    if (source_of(idx, d, s)) {
      for (int m = 0; m < nmat; ++m) a[m] = r[m] = en[m] = 0;
      return message_record(d, s, idx, [&](int m, Real am, Real rm, Real em) {
        a[m] = am;
        r[m] = rm;
        en[m] = em;
      });
    }
    return read(idx[0], idx[1], idx[2], a, r, en);  // as stored before the exchange
  }
  // content() as entries c < (the count returned) of material ids[c], ascending: the materials
  // the ghost's content holds, not all nmat (compact layout; MaterialState::assign, Sparse)
  static constexpr bool sparse = std::is_same_v<Dev, CompactDev>;
  KOKKOS_INLINE_FUNCTION int sparse_content(int i, int j, int k, int* ids, Real* a, Real* r,
                                            Real* en) const {
    int idx[3] = {i, j, k}, d = 0, s = 0;
    int c = 0;
    auto entry = [&](int m, Real am, Real rm, Real em) {
      ids[c] = m;
      a[c] = am;
      r[c] = rm;
      en[c] = em;
      ++c;
    };
    if (source_of(idx, d, s)) return message_record(d, s, idx, entry);
    if constexpr (sparse) {
      const int m = dev.mat(idx[0], idx[1], idx[2]);
      if (m >= 0) {
        entry(m, Real(1), rho(idx[0], idx[1], idx[2]), e(idx[0], idx[1], idx[2]));
        return 1;
      }
      const int f = dev.first(idx[0], idx[1], idx[2]), n = dev.nm(idx[0], idx[1], idx[2]);
      for (int q = f; q < f + n; ++q) entry(dev.smat(q), dev.salpha(q), dev.srho(q), dev.se(q));
      return n;
    } else {
      return 0;
    }
  }
};

// A compact cell is pure when it says so; a dense one when one material fills it (alpha
// exactly 1, every other exactly 0: then content() gives the same, bit for bit).
template <>
KOKKOS_INLINE_FUNCTION bool HaloSource<CompactDev>::stored_pure(int i, int j, int k, int& id,
                                                                Real& r, Real& en) const {
  const int m = dev.mat(i, j, k);
  if (m < 0) return false;
  id = m;
  r = rho(i, j, k);
  en = e(i, j, k);
  return true;
}
template <>
KOKKOS_INLINE_FUNCTION bool HaloSource<DenseDev>::stored_pure(int i, int j, int k, int& id, Real& r,
                                                              Real& en) const {
  int found = -1;
  for (int m = 0; m < nmat; ++m) {
    const Real a = dev.alpha(m, i, j, k);
    if (a == 0) continue;
    if (a != 1 || found >= 0) return false;
    found = m;
  }
  if (found < 0) return false;
  id = found;
  r = dev.rho(found, i, j, k);
  en = dev.e(found, i, j, k);
  return true;
}

template <>
KOKKOS_INLINE_FUNCTION int HaloSource<DenseDev>::read(int i, int j, int k, Real* a, Real* r,
                                                      Real* en) const {
  return read_cell(dev, i, j, k, a, r, en);
}
template <>
KOKKOS_INLINE_FUNCTION int HaloSource<CompactDev>::read(int i, int j, int k, Real* a, Real* r,
                                                        Real* en) const {
  return read_cell(dev, rho, e, i, j, k, a, r, en);
}

}  // namespace

void MaterialState::exchange() {
  Kokkos::Profiling::pushRegion("matter::exchange");  // named for profiling tools
  const int ng = Mesh::ng;
  const int nmat = nmat_;
  const int ext[3] = {ex_, ey_, ez_};
  // Messages carry a head per cell and records only of the cells that are not pure, only of
  // the materials present; the send buffer (one per side, reused by the sweeps) is sized for
  // the largest slab with every material in every cell, the receive buffers (per sweep and
  // side: the final update reads them all) for what arrived. Kept between calls.
  long largest = 0;
  for (int d = 0; d < 3; ++d) {
    int n[3] = {ext[0], ext[1], ext[2]};
    n[d] = ng;
    largest = std::max(largest, long(n[0]) * n[1] * n[2] * (3 + nmat * 3));
  }
  for (int s = 0; s < 2; ++s) {
    bool neighbour = false;
    for (int d = 0; d < 3; ++d)
      neighbour =
          neighbour || (!mesh_.physical_boundary(d, s) && mesh_.neighbor(d, s) != mesh_.rank());
    if (neighbour && long(send_[s].extent(0)) < largest)
      send_[s] = Buffer(Kokkos::view_alloc(Kokkos::WithoutInitializing, "matter::send"), largest);
  }
  if (pack_count_.extent(0) == 0) pack_count_ = decltype(pack_count_)("matter::pack_count", 6);
  if (kind_ == LayoutKind::Dense)
    exchange_layout(dense_);
  else
    exchange_layout(compact_);
  Kokkos::Profiling::popRegion();
}

// (a member function template, not a generic lambda: nvcc allows no extended lambda inside a
// generic lambda)
template <class Dev>
void MaterialState::exchange_layout(const Dev& dev) {
  const int ng = Mesh::ng;
  const int nmat = nmat_;
  const int ext[3] = {ex_, ey_, ez_};
  HaloSource<Dev> src{dev, rho_, e_, ng, nmat, 0, {ext[0], ext[1], ext[2]}, {}, {}, {}};
  for (int d = 0; d < 3; ++d) src.nl[d] = mesh_.owned_cells(d);
  for (int d = 0; d < 3; ++d) {
    const int nl = src.nl[d];
    bool any = false;
    long sent[2] = {0, 0};
    for (int s = 0; s < 2; ++s) {
      if (mesh_.physical_boundary(d, s)) {
        src.mode[d][s] = mesh_.boundary(d, s) == BoundaryKind::Reflective ? 1 : 2;
        continue;
      }
      if (mesh_.neighbor(d, s) == mesh_.rank()) {  // periodic, held by this rank alone
        src.mode[d][s] = 3;
        continue;
      }
      any = true;
      src.mode[d][s] = 0;
      // pack the ng owned layers next to face s, as they stand after the sweeps before d:
      // heads, and the records of the cells that are not pure where an atomic counter puts
      // them (their order varies from run to run; what each head points to does not)
      const int first = s == 0 ? ng : nl;
      int n[3] = {ext[0], ext[1], ext[2]};
      n[d] = ng;
      const long ncell = long(n[0]) * n[1] * n[2];
      auto buf = send_[s];
      // the counter runs on from exchange to exchange (resetting it would cost a launch):
      // this pack's records start where the last one on this sweep and side ended
      auto counter = Kokkos::subview(pack_count_, 2 * d + s);
      const long base = pack_total_[2 * d + s];
      const HaloSource<Dev> before = src;  // done == d
      Kokkos::parallel_for(
          "matter::pack", Kokkos::RangePolicy<ExecSpace, Kokkos::IndexType<long>>(0, ncell),
          KOKKOS_LAMBDA(long c) {
            int x[3] = {int(c / (long(n[1]) * n[2])), int((c / n[2]) % n[1]), int(c % n[2])};
            x[d] += first;
            int id = 0;
            Real pr = 0, pe = 0;
            if (before.pure(x[0], x[1], x[2], id, pr, pe)) {
              buf(c * 3) = -Real(id + 1);
              buf(c * 3 + 1) = pr;
              buf(c * 3 + 2) = pe;
              return;
            }
            Real a[kMaxMaterials], r[kMaxMaterials], en[kMaxMaterials];
            const int cnt = new_content(before, x[0], x[1], x[2], nmat, a, r, en, id);
            const long at = Kokkos::atomic_fetch_add(&counter(), long(3 * cnt)) - base;
            long o = 3 * ncell + at;
            int mask = 0;
            for (int m = 0; m < nmat; ++m) {
              if (!(a[m] > 0)) continue;
              mask |= 1 << m;
              buf(o) = a[m];
              buf(o + 1) = r[m];
              buf(o + 2) = en[m];
              o += 3;
            }
            buf(c * 3) = Real(mask);
            buf(c * 3 + 1) = Real(at / HaloSource<Dev>::kSplit);
            buf(c * 3 + 2) = Real(at % HaloSource<Dev>::kSplit);
          });
      long total = 0;
      Kokkos::deep_copy(total, counter);
      const long records = total - base;
      pack_total_[2 * d + s] = total;
      sent[s] = 3 * ncell + records;
    }
    if (any) {
      exchange_sized(mesh_, d, send_, sent, recv_[d], 100, "matter::recv");
      for (int s = 0; s < 2; ++s) src.recv[d][s] = recv_[d][s];
    }
    src.done = d + 1;
  }
  // one update of every ghost cell (one pool rebuild in the compact layout)
  assign("matter::halo", src);
}

}  // namespace mp::mat
