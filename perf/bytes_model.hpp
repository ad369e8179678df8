// The counted traffic model of the single-material cycle: for every kernel, the fields it reads
// and writes and the index range it runs over (read from kernels/hydro/*.cpp and
// src/mesh/halo.cpp), so bytes = points of the range x (fields read + fields written) x
// sizeof(Real), per call, times the calls in a cycle. One table for every benchmark.
//
// What "counted" means here, and what it leaves out:
//  - each distinct field a kernel touches is charged once per point of its range (compulsory
//    traffic: the stencil neighbours of a point are assumed to come from cache);
//  - a write is charged once, as STREAM's triad charges its store (no write-allocate), so the
//    ratio to the triad compares like with like;
//  - a node field read by a cell kernel (or a cell field by a node kernel) is charged over the
//    kernel's own range (the two differ by one layer: (n+1)^3 against n^3);
//  - halo::fill: every ghost point of every field of each of the cycle's 11 exchanges (the
//    shell of the block: its extent less the interior, each point written once as the one-rank
//    fill does), read once (source) and written once; the reflective wall nodes it zeroes (one
//    layer) are not counted; with neighbour ranks the per-axis fills and packs move more;
//  - scalar reductions and MPI carry no field traffic.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "mesh/mesh.hpp"

namespace mp::perf {

// Index ranges of the single-material kernels, per rank (n: owned cells along an axis,
// E = n + 2 ng the cell extent with ghosts, N = E + 1 the node extent).
enum class Range {
  CellsOwned,    // n^3: mesh.cells(Owned)
  CellsAll,      // E^3: mesh.cells(All)
  CellsPadded1,  // (n + 2)^3: mesh.cells_padded(1)
  NodesOwned,    // (n + 1)^3: mesh.nodes(Owned)
  NodeInterior,  // (E - 1)^3: remap::node_mass, nodes [1, E)
  FacesOwned,    // (n + 1) E^2: remap::cell_flux, owned faces along the sweep, all rows across
  DualFaces,     // (n + 2)(n + 1)^2: remap::dual_face, both dual faces of every owned node
  HaloGhosts,    // every ghost point of the cycle's exchanges (see halo_points)
};

struct KernelTraffic {
  const char* name;
  Range range;
  int reads, writes;   // distinct fields
  int calls;           // per single-material split-remap cycle
  const char* fields;  // what is read -> what is written
};

// The single-material split-remap cycle (Hydro::time_step, lagrange, remap x 3 sweeps,
// equation_of_state, viscosity, check) with the fixed geometry, kernels/hydro at the commit this
// was counted on.
inline const std::vector<KernelTraffic>& fixed_cycle_table() {
  static const std::vector<KernelTraffic> t = {
      {"timestep::cfl", Range::CellsOwned, 6, 0, 1, "c q rho u v w ->"},
      // the six face volume fluxes of each cell found from the node velocities in the kernel
      {"lagrange::predictor", Range::CellsAll, 7, 1, 1, "u v w rho e p q -> p_half"},
      {"lagrange::acceleration", Range::NodesOwned, 6, 6, 1,
       "p_half q rho u v w -> u v w ub vb wb"},
      // (stores the face fluxes for the remap and the first sweep's cell volumes, and counts the
      // non-positive Lagrangian volumes of owned cells)
      {"lagrange::corrector", Range::CellsAll, 7, 7, 1,
       "ub vb wb rho e p_half q -> fx fy fz e rho pre post"},
      // p and c, then q over the padded cells from the jumps (q = 0 in the outer ghost layer)
      {"lagrange::eos_viscosity", Range::CellsAll, 2, 3, 1, "rho e -> p c q"},
      {"lagrange::eos_viscosity", Range::CellsPadded1, 3, 0, 1, "u v w ->"},
      {"health::check", Range::CellsOwned, 3, 0, 1, "rho e p ->"},
      {"health::check", Range::NodesOwned, 3, 0, 1, "u v w ->"},
      {"remap::node_mass", Range::NodeInterior, 2, 1, 3, "rho pre -> node_mass"},
      {"remap::cell_flux", Range::FacesOwned, 4, 2, 3,
       "vol_flux pre rho e -> mass_flux energy_flux"},
      {"remap::cell_update", Range::CellsPadded1, 6, 2, 3,
       "rho e pre post mass_flux energy_flux -> rho e"},
      {"remap::dual_face", Range::DualFaces, 5, 4, 3, "mass_flux u v w node_mass -> F U V W"},
      {"remap::momentum", Range::NodesOwned, 8, 4, 3,
       "u v w node_mass F U V W -> ub vb wb ke_loss"},
      {"remap::ke_fix", Range::CellsOwned, 4, 1, 3, "ke_loss rho post e -> e"},
      // the next sweep's cell volumes (the first two sweeps; the first sweep's: the corrector)
      {"remap::ke_fix", Range::CellsAll, 3, 2, 2, "fx fy fz -> pre post"},
      {"halo::fill", Range::HaloGhosts, 1, 1, 11, "ghost source -> ghost (per field)"},
  };
  return t;
}

// The cycle's table; `mid`: with the mid-step geometry (Hydro::mid_geometry), whose Lagrangian
// step differs: the predictor also copies the start-of-step velocities (u0 v0 w0), the
// acceleration reads them for its face corrections, lagrange::mid_faces stores each face's flux
// once from them and the half-step velocities, and the corrector reads those.
inline const std::vector<KernelTraffic>& cycle_table(bool mid = false) {
  static const std::vector<KernelTraffic> with_mid = [] {
    const std::vector<KernelTraffic> rows = {
        {"lagrange::predictor", Range::CellsAll, 7, 4, 1, "u v w rho e p q -> p_half u0 v0 w0"},
        {"lagrange::acceleration", Range::NodesOwned, 9, 6, 1,
         "p_half q rho u v w u0 v0 w0 -> u v w ub vb wb"},
        {"lagrange::mid_faces", Range::CellsAll, 6, 3, 1, "ub vb wb u0 v0 w0 -> fx fy fz"},
        {"lagrange::corrector", Range::CellsAll, 10, 4, 1,
         "ub vb wb rho e p_half q fx fy fz -> e rho pre post"},
    };
    std::vector<KernelTraffic> t;
    for (const KernelTraffic& k : fixed_cycle_table()) {
      const std::string name = k.name;
      if (name == "lagrange::predictor")
        t.insert(t.end(), rows.begin(), rows.end());
      else if (name != "lagrange::acceleration" && name != "lagrange::corrector")
        t.push_back(k);
    }
    return t;
  }();
  return mid ? with_mid : fixed_cycle_table();
}

// Ghost points x fields of the cycle's 11 field exchanges: the view's extent less its
// interior (2 ng ghost layers per axis), per field.
inline double halo_points(const Mesh& m) {
  const int ng = Mesh::ng;
  double E[3], N[3];
  for (int d = 0; d < 3; ++d) {
    E[d] = m.extent(Centering::Cell, d);
    N[d] = m.extent(Centering::Node, d);
  }
  auto exchange = [&](int fields, const double* ext) {
    return fields *
           (ext[0] * ext[1] * ext[2] - (ext[0] - 2 * ng) * (ext[1] - 2 * ng) * (ext[2] - 2 * ng));
  };
  double pts = exchange(6, N) + 4 * exchange(2, E) + 3 * exchange(3, N);
  for (int f = 0; f < 3; ++f) {  // face fluxes normal to f: node-like along f, cell-like across
    double ext[3] = {E[0], E[1], E[2]};
    ext[f] = N[f];
    pts += exchange(2, ext);
  }
  return pts;
}

inline double range_points(const Mesh& m, Range r) {
  const int ng = Mesh::ng;
  double n[3], E[3];
  for (int d = 0; d < 3; ++d) {
    n[d] = m.owned_cells(d);
    E[d] = n[d] + 2 * ng;
  }
  switch (r) {
    case Range::CellsOwned:
      return n[0] * n[1] * n[2];
    case Range::CellsAll:
      return E[0] * E[1] * E[2];
    case Range::CellsPadded1:
      return (n[0] + 2) * (n[1] + 2) * (n[2] + 2);
    case Range::NodesOwned:
      return (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
    case Range::NodeInterior:
      return (E[0] - 1) * (E[1] - 1) * (E[2] - 1);
    case Range::FacesOwned:  // the mean over the three sweeps
      return ((n[0] + 1) * E[1] * E[2] + E[0] * (n[1] + 1) * E[2] + E[0] * E[1] * (n[2] + 1)) / 3;
    case Range::DualFaces:
      return ((n[0] + 2) * (n[1] + 1) * (n[2] + 1) + (n[0] + 1) * (n[1] + 2) * (n[2] + 1) +
              (n[0] + 1) * (n[1] + 1) * (n[2] + 2)) /
             3;
    case Range::HaloGhosts:
      return halo_points(m) / 11;  // per call, the mean over the cycle's 11 fills (one rank)
  }
  return 0;
}

// Bytes a kernel moves in one cycle under the model (calls x points x fields x sizeof(Real)).
inline double cycle_bytes(const Mesh& m, const KernelTraffic& k) {
  return double(k.calls) * range_points(m, k.range) * (k.reads + k.writes) * sizeof(Real);
}

// Bytes per cycle of every kernel of the table, by name (a fused kernel has a row per part).
inline std::map<std::string, double> cycle_bytes(const Mesh& m, bool mid = false) {
  std::map<std::string, double> out;
  for (const auto& k : cycle_table(mid)) out[k.name] += cycle_bytes(m, k);
  return out;
}

}  // namespace mp::perf
