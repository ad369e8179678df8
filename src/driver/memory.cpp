// The run's memory estimate from the allocations a probe run makes (driver/memory.hpp).
#include "driver/memory.hpp"

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "burn/lighting.hpp"
#include "burn/lighting_device.hpp"
#include "core/error.hpp"
#include "core/memory.hpp"
#include "driver/simulation.hpp"

namespace mp {

namespace {

// Cells of the probe mesh (about; 41 x 8 x 13 for the perforator): set-up and two cycles of
// the perforator take 0.1 s there. Axes of up to kKeptAxis cells keep their count.
constexpr long kProbeCells = 4096;
constexpr int kKeptAxis = 4;
// Resident memory the HDF5 output adds to a run beyond its arrays: 5.3 MiB observed (sod_z,
// 20 cycles, 1 rank: peak RSS 33.9 MiB with output.write true, 28.6 MiB with false).
constexpr double kHdf5Bytes = 5.5 * 1024 * 1024;
// Bytes a Kokkos View's allocation may exceed its span by (rounded up to a multiple of 8).
constexpr double kAllocationRounding = 8;
// Fields one halo exchange carries at most (src/mesh/halo.cpp: two to six).
constexpr int kHaloFields = 6;

// The probe's cells per axis for a mesh of `n`: every longer axis scaled by one factor, so the
// probe keeps the box's shape, to about `target` cells in all.
std::array<int, 3> probe_cells(const std::array<int, 3>& n, long target) {
  double total = 1;
  int scaled = 0;
  for (int d = 0; d < 3; ++d) {
    total *= n[d];
    if (n[d] > kKeptAxis) ++scaled;
  }
  if (total <= double(target) || scaled == 0) return n;
  const double f = std::pow(double(target) / total, 1.0 / scaled);
  std::array<int, 3> p = n;
  for (int d = 0; d < 3; ++d)
    if (n[d] > kKeptAxis) p[d] = std::max(kKeptAxis, int(std::lround(n[d] * f)));
  return p;
}

double extent_product(const Mesh& m, Centering c) {
  double p = 1;
  for (int d = 0; d < 3; ++d) p *= m.extent(c, d);
  return p;
}

// Resident memory of this process now (VmRSS), bytes.
double resident_bytes() {
  std::ifstream in("/proc/self/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;
  return 0;
}

bool checkpoints_on(const Scene& s) {
  return s.output.checkpoint_cycles > 0 || s.output.checkpoint_seconds > 0;
}

// Bytes per global cell that every rank holds for the lighting times beside its Kokkos cell
// arrays: the host construction's global arrays (burn.lighting: host), or the per-rank
// construction's explosive bit mask (its labels are cell arrays of the block, which the probe
// weighs with the rest); 0 without programmed burn.
double lighting_bytes_per_cell(const Scene& s) {
  for (const auto& m : s.materials)
    if (m.burn.on && m.burn.programmed)
      return m.burn.host_lighting ? burn::kLightingHostBytesPerCell
                                  : burn::kLightingMaskBytesPerCell;
  return 0;
}

// One probe run at `cells`: the scene set up and run two cycles on this rank alone, its
// allocations weighed by `weights` (cell arrays, node arrays, the rest) as they are made.
// Returns the weighted parts at the peak and after the set-up.
void probe_run(const Scene& scene, const std::array<int, 3>& cells, const Mesh& block,
               std::vector<double>& at_peak, std::vector<double>& after_setup) {
  Scene ps = scene;
  ps.mesh.cells = cells;
  ps.mesh.ranks = {0, 0, 0};
  const Mesh pm(ps.mesh, MPI_COMM_SELF);
  const double pc = extent_product(pm, Centering::Cell), pn = extent_product(pm, Centering::Node);
  // the rest (pools, mixed lists) grows with the interface cells: (h_probe / h)^(D - 1) on a
  // D-dimensional mesh, and this rank holds its share of them
  double ratio = 1;
  int dims = 0;
  for (int d = 0; d < 3; ++d)
    if (scene.mesh.cells[d] > 1) {
      ratio *= double(scene.mesh.cells[d]) / cells[d];
      ++dims;
    }
  const double interface = dims > 0 ? std::pow(ratio, double(dims - 1) / dims) : 1;
  const double share = double(block.owned_cell_count()) / double(block.global_cell_count());

  AllocationTracker tracker(true);
  tracker.weigh(
      [pc, pn](uint64_t bytes) {
        const double b = double(bytes);
        // a View's allocation is its span rounded up to 8 bytes (Kokkos' ViewMapping): a float
        // array of an odd number of points is 4 bytes over the multiple
        if (b >= pc && std::fmod(b, pc) < kAllocationRounding) return 0;
        if (b >= pn && std::fmod(b, pn) < kAllocationRounding) return 1;
        return 2;
      },
      {extent_product(block, Centering::Cell) / pc, extent_product(block, Centering::Node) / pn,
       interface * share});
  RunSettings quiet;
  quiet.quiet = true;
  Simulation sim(ps, MPI_COMM_SELF, quiet);
  // the arrays a dump or a checkpoint computes live beside the run's for its writing
  auto output = [&] {
    if (ps.output.write) sim.dump_fields();
    if (checkpoints_on(ps)) sim.checkpoint_fields();
  };
  sim.initialize();
  after_setup = tracker.live_parts();
  output();
  Real dt_old = 0;
  double t = 0;
  // the cycles reach the arrays made on first use (pools' growth, scratch); a coarse probe that
  // goes non-physical where the deck's mesh would not keeps the peak it reached: the estimate
  // is the probe's, the run's own health checks are the run's
  try {
    for (long cycle = 0; cycle < 2; ++cycle) {
      hydro::TimeStep ts = sim.hydro().time_step(dt_old, t, ps.time.end);
      if (cycle == 0) ts.dt = std::min(ts.dt, Real(ps.time.dt_initial));
      sim.hydro().step(ts.dt, cycle);
      t += double(ts.dt);
      dt_old = ts.dt;
    }
    output();
  } catch (const RunError&) {
  }
  at_peak = tracker.parts_at_peak();
}

}  // namespace

std::string mib(double bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f MiB", bytes / (1024.0 * 1024.0));
  return b;
}

std::string MemoryEstimate::text() const {
  std::string s = mib(total()) + " (cell arrays " + mib(cells) + ", node arrays " + mib(nodes) +
                  ", pools and other " + mib(other);
  if (lighting > 0) s += ", lighting times " + mib(lighting);
  if (halo > 0) s += ", halo buffers " + mib(halo);
  if (output > 0) s += ", output " + mib(output);
  return s + ", process " + mib(process) + ")";
}

MemoryEstimate estimate_memory(const Scene& scene, const Mesh& block) {
  std::vector<double> at_peak, after_setup;
  // A coarse probe may fail where the deck does not (a detonator lighting no cell that is at
  // least half explosive): the next probe has 8 times the cells, up to the deck's mesh or the
  // rank's block, whichever is smaller (a probe never takes more than the run would); the
  // last one's error is the deck's.
  const long most = std::max(kProbeCells, long(block.owned_cell_count()));
  for (long target = kProbeCells;; target *= 8) {
    const std::array<int, 3> cells = probe_cells(scene.mesh.cells, std::min(target, most));
    try {
      probe_run(scene, cells, block, at_peak, after_setup);
      break;
    } catch (const InputError&) {
      if (cells == scene.mesh.cells || target >= most) throw;
    }
  }
  MemoryEstimate e;
  // the lighting times are built in the set-up, beside what it allocated
  e.lighting = lighting_bytes_per_cell(scene) * double(block.global_cell_count());
  std::vector<double> parts = at_peak;
  double peak = 0, setup = e.lighting;
  for (std::size_t c = 0; c < parts.size(); ++c) {
    peak += at_peak[c];
    setup += after_setup[c];
  }
  if (setup > peak)
    parts = after_setup;
  else
    e.lighting = 0;
  e.cells = parts[0];
  e.nodes = parts[1];
  e.other = parts[2];
  // send and receive buffers, both sides, sized for the largest face of node extents
  bool neighbours = false;
  double face = 0;
  for (int d = 0; d < 3; ++d) {
    for (int s = 0; s < 2; ++s)
      neighbours =
          neighbours || (!block.physical_boundary(d, s) && block.neighbor(d, s) != block.rank());
    face =
        std::max(face, extent_product(block, Centering::Node) / block.extent(Centering::Node, d));
  }
  // writing: the HDF5 library (MPI-IO, its caches) and the host copy of one field's owned block
  // that the writer stages (src/io/h5_util.cpp)
  if (scene.output.write || checkpoints_on(scene)) {
    double owned_nodes = 1;
    for (int d = 0; d < 3; ++d) owned_nodes *= block.owned_cells(d) + 1;
    e.output = kHdf5Bytes + owned_nodes * sizeof(Real);
  }
  if (neighbours) e.halo = 4.0 * kHaloFields * Mesh::ng * face * sizeof(Real);
  // what the probe freed goes back to the system before the process is measured
  malloc_trim(0);
  e.process = resident_bytes();
  return e;
}

}  // namespace mp
