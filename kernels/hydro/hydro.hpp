// The hydro of every scene: a predictor-corrector Lagrangian step on the staggered grid followed
// by a remap back to the fixed mesh (docs/numerics.md, "One cycle"). Cell-averaged fields live
// here; the per-material state of multi-material scenes (materials/layout.hpp) and the physics
// modules (strength, burn) plug in beside them. Its options: Options below, built from the typed
// numerics of hydro/numerics.hpp; its point functions: point.hpp, faces.hpp, ke_fix.hpp.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/columns.hpp"
#include "core/error.hpp"
#include "eos/eos.hpp"
#include "hydro/faces.hpp"
#include "hydro/ke_fix.hpp"
#include "hydro/module.hpp"
#include "hydro/numerics.hpp"
#include "hydro/point.hpp"
#include "materials/layout.hpp"
#include "mesh/field.hpp"
#include "mesh/halo.hpp"
#include "mesh/mesh.hpp"

namespace mp::hydro {

// Most module carriers a scene can have: one per material with strength, and the explosive.
constexpr int kMaxCarriers = mat::kMaxMaterials + 1;

// The smallest volume fraction a material may hold beside others: 4 ulps of 1 in Real. Below
// it the largest material's fraction 1 - f rounds to 1 (in float from f < 2^-25 = 3e-8), so a cell
// would read as pure in the dense layout (alpha == 1) and mixed in the compact one, and its
// volume would not sum to the cell's. 8.9e-16 in double builds (below the 1e-14 default), 4.8e-7
// in float builds.
constexpr double kMinFractionFloor = 4.0 * double(std::numeric_limits<Real>::epsilon());

// The min_fraction a run uses: the deck's, raised to the floor above.
inline double effective_min_fraction(double requested) {
  return std::max(requested, kMinFractionFloor);
}

struct Options {
  // The deck's numerics (numerics.hpp holds their one set of defaults; Options() takes them).
  Options() : Options(Numerics{}, StepControl{}) {}
  Options(const Numerics& n, const StepControl& t);

  int order;  // advection order: 2 van Leer, 1 donor cell, 3 third order (numerics.advection);
  // -2, -3 the same without the limiter (set_unlimited)
  Real q_linear;
  Real q_quadratic;
  // the viscous stress Q = q ((1 - b) S + b I), b = q_isotropic (point.hpp): 0 the tensor, 1 the
  // scalar q of a pressure
  Real q_isotropic;
  // Noh's artificial heat flux (conduction.cpp): the coefficient h of the conduction of
  // internal energy between face neighbours that the viscosity compresses; 0 turns it off.
  // Single-material scenes (a multi-material scene ignores it).
  Real heat_flux;
  // The Lagrangian step's pressure forces on the mid-step geometry (docs/numerics.md, "Mid-step
  // geometry"): each face's corner vectors at its nodes moved by dt/2 u^n, the cell's work the
  // forces' work (total energy kept to round-off), its volume change the matching second-order
  // face volumes. Off: the undeformed cube's faces (first order in dt where flow converges or
  // diverges across a face). Single-material scenes without strength; the others ignore it.
  bool mid_geometry;  // (the scene key numerics.geometry)
  // The free-expansion rule (point.hpp expansion_share; docs/numerics.md, "Free expansion to
  // the nodes"): a face whose gas enters a cell that would hold less than this fraction of the
  // face's density gives the receiver the isentropically expanded energy and its nodes the
  // rest as kinetic energy of the node pairs it pushes apart; 0 turns it off. Single-material
  // ideal-gas scenes on split sweeps with the KE fix (the others ignore it).
  Real free_expansion;
  Real cfl;
  // Time-step rule (time.rule; numerics.hpp StepRule, diagnostics.cpp CflCells). Combined:
  // dt = cfl min_d dx_d / (c_eff + |u_d|). Separate: the sound speed and the transport speed
  // limit the step each on its own, with its own safety factor: dt = min_d min(cfl dx_d / c_eff,
  // cfl_transport dx_d / |u_d|). CloverLeaf: CloverLeaf3D_ref's sound, face-velocity and
  // divergence limits. perf/timestep_study.py measures them on the verification scenes;
  // docs/numerics.md says why the default is what it is.
  StepRule rule;
  Real cfl_transport;
  Real growth;
  Real dt_max;
  // Give the kinetic energy that the momentum remap dissipates back to the cells as internal
  // energy (DeBar's correction, see Benson, Comput. Methods Appl. Mech. Eng. 99:235, 1992),
  // so total energy is conserved to round-off.
  bool ke_fix;
  // Multi-material scenes: a node's loss goes to its 8 cells in proportion to their mass (every
  // cell takes the same specific energy; numerics.ke_fix_share: mass, the default) or an eighth
  // to each (equal, the rule before 2026-12-03). Single-material scenes have their own budget
  // (ke_fix_share() above) and ignore it.
  bool ke_fix_by_mass;
  // Single-material scenes: where a node made more kinetic energy than its cells can pay
  // (ke_redo), redo its dual faces with donor values (numerics.ke_fix_redo; remap.cpp).
  bool ke_fix_redo;
  // One remap step over all axes instead of three split sweeps (symmetric under permutations
  // of the axes; the time step then keeps the sum of the axes' Courant numbers below cfl).
  bool unsplit;
  // Multi-material scenes (two or more EOS): storage of the per-material state, interface
  // reconstruction of the material fluxes (Youngs PLIC, SLIC, or none: fraction-weighted),
  // and the volume fraction below which a material leaves a cell (its mass and energy go to
  // the largest material of the cell).
  mat::LayoutKind layout;
  Interface interface;
  Real min_fraction;  // the deck's, raised to kMinFractionFloor
  // Mixed-cell closure of the Lagrangian step: equal strain (false), or equal strain followed
  // by pressure relaxation (true, kernels/hydro/relax.hpp) with at most relax_iterations
  // Newton updates per cycle, stopping once the pressures agree to relax_tol (relative).
  bool relax;
  int relax_iterations;
  // Solid floor (docs/numerics.md, "Stretched solids in mixed cells"): a Mie-Grueneisen
  // material of a mixed cell below solid_floor x rho0 after the corrector is put back at that
  // density, its volume going to the cell's other materials without work (free expansion into
  // the void a failing solid opens); 0 leaves equal strain alone.
  Real solid_floor;
  // (1e-10, or 64 ulps where Real cannot hold that: 7.6e-6 in float)
  Real relax_tol = Real(std::max(1e-10, 64.0 * double(std::numeric_limits<Real>::epsilon())));
};

struct State {
  // cells
  Field3 rho, e, p, c, q;
  // the tensor viscosity Q = q S (point.hpp, compression_direction): xx, yy, zz, xy, xz, yz
  std::array<Field3, 6> qt;
  // per cell column (i, j): 1 where some cell of it has a viscous stress (the Lagrangian
  // kernels skip the stress of the columns without)
  Kokkos::View<int**, MemSpace> qcol;
  // Noh's heat flux (conduction.cpp; single-material scenes with numerics.heat_flux > 0): each
  // cell's compressive velocity jump where it converges (0 elsewhere), and a flag the
  // viscosity raises where any cell of the rank converges
  Field3 cjump;
  Kokkos::View<int, MemSpace> converging;
  // the energy the KE fix's floor left uncharged on this rank's owned cells since the start
  // (remap.cpp ke_fix_cell, mixed_ke_fix.cpp MixedKeFix / PureKeFix; reported by totals())
  Kokkos::View<double, MemSpace> ke_unpaid;
  // raised by remap::momentum where a node made kinetic energy its cells cannot pay (ke_redo)
  Kokkos::View<int, MemSpace> ke_redo;
  Field3 qw;  // a multi-material step's viscous work per cell (the corrector's, for its materials)
  Field3 p_half;             // pressure at the half step (predictor)
  Field3 pre_vol, post_vol;  // cell volumes before / after one remap sweep
  // nodes
  Field3 u, v, w;     // velocity
  Field3 ub, vb, wb;  // time-centred velocity of the Lagrangian step
  Field3 node_mass;   // remap scratch: nodal (dual-cell) mass before a sweep
  Field3 ke_loss;     // remap scratch: kinetic energy the momentum remap took from a node
                      // (multi-material, shares by mass: over 8 times the node's mass)
  // remap scratch of a split sweep: mass flux and upwind velocities of the dual face above
  // each node along the sweep's axis
  Field3 dual_flux, dual_u, dual_v, dual_w, dual_k;  // dual_k: kinetic energy carried per unit mass
  // faces, stored in node-extent views: face d at index i sits at node coordinate i along d
  std::array<Field3, 3> vol_flux;
  std::array<Field3, 3> mass_flux, energy_flux;  // through faces normal to x, y, z
  // the free-expansion rule (Options::free_expansion): the internal energy a face's donor pays
  // beyond what its receiver takes, given to the face's node pairs as kinetic energy (allocated
  // only where the rule can act; the unsplit step keeps one per axis, [0] being expansion_work,
  // since it pays every axis's work in one cell update; a split sweep uses [0] alone)
  Field3 expansion_work;
  std::array<Field3, 3> expansion_work_axis;
  Kokkos::View<int, MemSpace> expansion_any;  // set where a sweep's faces did that work
};

// What limited a time step: the CFL condition per axis, the unsplit remap's sum of the axes'
// Courant numbers, the growth factor, dt_max, the end time; the driver's first step held at
// time.dt_initial. dt_limit_name gives the run log's word for each.
enum class DtLimit { Cfl, CourantSum, Growth, Max, End, Initial };
inline const char* dt_limit_name(DtLimit l) {
  switch (l) {
    case DtLimit::Cfl:
      return "cfl";
    case DtLimit::CourantSum:
      return "courant_sum";
    case DtLimit::Growth:
      return "growth";
    case DtLimit::Max:
      return "max";
    case DtLimit::End:
      return "end";
    case DtLimit::Initial:
      return "initial";
  }
  return "?";
}

struct TimeStep {
  Real dt = 0;
  std::array<int, 3> cell{{-1, -1, -1}};  // global index of the limiting cell
  DtLimit limit = DtLimit::Cfl;
};

struct Totals {
  double mass = 0, internal = 0, kinetic = 0;
  std::array<double, 3> momentum{};
  // the energy the KE fix could not charge since the run began: where the remap made kinetic
  // energy its cells could not pay without falling below ke_fix_floor (point.hpp), the total
  // energy gains this much (0 in every shipped deck)
  double ke_fix_unpaid = 0;
  std::vector<double> material_mass;  // per material (multi-material scenes)
  double total() const { return internal + kinetic; }
};

// The first cell (lowest global index) that went non-physical, if any.
struct Health {
  bool ok = true;
  std::array<int, 3> cell{};
  double rho = 0, e = 0, p = 0, volume = 0;
  std::string what;
  // A bad material of a mixed cell (what names it): its id (-1: none) and its own state there.
  int material = -1;
  double m_fraction = 0, m_rho = 0, m_e = 0;
};

class Hydro {
 public:
  Hydro(const Mesh& mesh, Halo& halo, const Options& opt, eos::Eos eos);
  // One EOS per material; two or more switch the multi-material path on.
  Hydro(const Mesh& mesh, Halo& halo, const Options& opt, const std::vector<eos::Eos>& eos);

  State& state() { return s_; }
  const State& state() const { return s_; }
  const Options& options() const { return opt_; }
  // whether this step runs the mid-step geometry (Options::mid_geometry, where it applies)
  bool mid_geometry() const { return mid_geometry_; }
  // Switches the time-step rule (the scene reader sets it from time.rule; tests).
  void set_time_rule(StepRule rule, Real cfl_transport) {
    opt_.rule = rule;
    opt_.cfl_transport = cfl_transport;
  }
  // Switches the remap's monotonicity limiter off (verification only: the scene reader does
  // not set it; tests/test_hydro.cpp measures the third-order slope's unlimited order with it).
  // The face values then take the unbounded slopes (remap::face_value, negative orders), which
  // oscillate at a discontinuity. Single-material scenes only (throws otherwise).
  void set_unlimited() {
    if (mm_) throw RunError("Hydro::set_unlimited: single-material scenes only");
    if (opt_.order > 1) opt_.order = -opt_.order;
  }
  // The per-material state of a multi-material scene, or nullptr.
  mat::MaterialState* materials() { return mm_.get(); }
  const mat::MaterialState* materials() const { return mm_.get(); }
  // Adds a physics module (module.hpp; the driver builds those the scene needs, before the
  // first prepare()): its carriers, its EOS closure, and what it turns off (the mid-step
  // geometry where it adds forces; the free-expansion rule, which runs without modules).
  void add_module(std::unique_ptr<Module> m);
  // The scene's modules, in the order they were added (strength, then burn), and the fields
  // they register that `use` (FieldUse bits) selects.
  std::vector<Module*> modules() const;
  std::vector<FieldSpec> module_fields(unsigned use) const;
  // The module of type M, or nullptr (for tests and tools that read a module's own fields).
  template <class M>
  M* module() const {
    for (const auto& m : modules_)
      if (M* p = dynamic_cast<M*>(m.get())) return p;
    return nullptr;
  }

  // Fills ghosts of the primary fields and derives p, c, q (call after setting rho, e, u, v, w).
  void prepare();
  // p and c from the EOS, then q (a plain single-material scene does both in one launch).
  void eos_viscosity();
  TimeStep time_step(Real dt_old, double t, double t_end) const;
  // One full cycle: Lagrangian step then remap; `cycle` sets the sweep order. Returns the
  // health of the Lagrangian volumes (a run stops when they collapse).
  Health step(Real dt, long cycle);
  Health check() const;
  Totals totals() const;
  std::vector<OutputField> output_fields() const;

  // Exposed for tests.
  void equation_of_state(const Field3& rho, const Field3& e, const Field3& p,
                         const Field3& c) const;
  void viscosity();
  // The Lagrangian step; `cycle`, the cycle whose remap follows, lets the corrector write the
  // first remap step's cell volumes (any other remap recomputes them).
  Health lagrange(Real dt, long cycle = 0);
  void remap(long cycle);
  // sweeps whose dual faces the KE fix redid with donor values so far (ke_redo; the same on
  // every rank)
  long ke_redone() const { return ke_redone_; }
  // One remap step over the faces normal to `axes`; `pending` marks the axes whose volume
  // change is not yet remapped (the step's own included).
  void remap_step(const std::array<bool, 3>& axes, const std::array<bool, 3>& pending);
  struct RemapStep {
    std::array<bool, 3> axes, pending;
    bool operator==(const RemapStep& o) const { return axes == o.axes && pending == o.pending; }
    StepWeights weights() const {
      return {Real(pending[0]), Real(pending[1]), Real(pending[2]),
              Real(axes[0]),    Real(axes[1]),    Real(axes[2])};
    }
  };
  // The remap steps of a cycle, in order: x, y, z on even cycles and z, y, x on odd ones, or
  // the one unsplit step.
  std::vector<RemapStep> remap_steps(long cycle) const;

  // Kernel launchers (public: nvcc requires the function enclosing an extended
  // __host__ __device__ lambda to be public).
  // The boundary mass ledger (ledger.cpp; output.mass_ledger): off until switched on, before
  // the first cycle. mass_ledger(): per material (one entry for a single-material scene), the
  // mass out through the faces x lo, x hi, y lo, y hi, z lo, z hi (6 m + 2 d + side) since the
  // run began, summed over the ranks (collective); empty when off. restore_mass_ledger(): a
  // restart's, from the checkpoint.
  void set_mass_ledger(bool on);
  bool mass_ledger_on() const { return !ledger_.empty(); }
  std::vector<double> mass_ledger() const;
  void restore_mass_ledger(const std::vector<double>& global);
  struct NoLayout {};  // (a single-material scene's ledger_faces)
  template <class Dev>
  void ledger_faces(const Dev& dev, int d);
  void ledger_sweep(int d);
  void exchange_cells();
  // Noh's heat flux over a step dt (conduction.cpp), before the Lagrangian step: the number of
  // explicit sub-steps it took, 0 where it did nothing (off, a multi-material scene, no
  // converging cell).
  int heat_flux(Real dt);
  // whether the scene conducts (Noh's heat flux on, a single material)
  bool conducts() const { return opt_.heat_flux > 0 && !mm_; }
  // whether the free-expansion rule acts (Options::free_expansion; single-material ideal gas,
  // split sweeps, no modules)
  bool free_expansion_acts() const { return expansion_gm1_ > 0; }
  // The free-expansion work of the sweep along d given to its nodes (remap_sweep.cpp).
  void expansion_impulse(int d);
  void exchange_nodes(const Field3& u, const Field3& v, const Field3& w);
  // After remap::momentum: whether a node on any rank raised State::ke_redo (with the option
  // on); if so the node losses are exchanged (their ghosts hold their owners' flags) and the
  // sweep counted, the caller redoes the flagged nodes' faces, then ke_redo_end lowers the flag.
  bool ke_redo_begin();
  void ke_redo_end();
  // `next`: the step after this one (nullptr for the last), whose cell volumes the KE fix's
  // launch writes.
  void remap_step(const RemapStep& step, const RemapStep* next);
  // A single-material scene without modules, whose EOS and viscosity are one launch
  // (the modules adjust p and c between the two).
  bool plain() const { return !mm_ && modules_.empty(); }
  void viscosity_with(bool with_eos);
  // Multi-material pieces (mixed_lagrange.cpp, mixed_remap_faces.cpp, mixed_remap_cells.cpp,
  // mixed_ke_fix.cpp).
  void mm_equation_of_state() const;
  // (`f`: the half step's face factors, dt/2 times a quarter of each axis's face area)
  void mm_predictor(Real vol, const std::array<Real, 3>& f);
  void mm_corrector(Real vol);
  template <class Dev>
  void mm_face_fluxes(const Dev& dev, int d);
  template <class Dev>
  void mm_cell_update(const Dev& dev, int d);
  void mm_remap_faces(int d);
  void mm_remap_cells(int d);
  // (`next`: as remap_step's; the compact layout's pure launch then writes its volumes)
  void mm_ke_fix(const RemapStep* next);
  // The carriers' densities of a remap step (before the cell update).
  void mm_carriers();
  // After the cell update: a cell its carrier left (through a face, or as a sliver below
  // min_fraction) holds none of the module's quantities.
  void mm_clear_absent();
  // The mass fluxes (face field of the sweep's axis) and densities the module quantities ride
  // on (module.hpp Carrier): a single-material scene's cell ones, or a multi-material scene's
  // carrier `slot`; and module i's carriers in its carriers() order.
  Carrier carrier(int slot) const;
  std::vector<Carrier> carriers_of(std::size_t i) const;

 private:
  const Mesh& mesh_;
  Halo& halo_;
  Options opt_;
  eos::Eos eos_;
  mat::MaterialSet mats_;
  std::unique_ptr<mat::MaterialState> mm_;
  // The physics modules (module.hpp), and the first carrier slot and number of carriers of
  // each; the one whose EOS closure the EOS kernels evaluate (an explosive), if any.
  std::vector<std::unique_ptr<Module>> modules_;
  std::vector<int> first_carrier_, carriers_;
  const eos::Reactive* reactive_ = nullptr;
  // Multi-material scenes with modules: the materials whose mass carries each module's cell
  // quantities (the modules' carriers(), in the order they were added: the strength module's
  // stress sets, each its own material, then the burn module's explosive), their mass flux
  // through the faces of the sweep (written by the material flux kernel) and their density
  // (sum alpha_m rho_m over them).
  int ncarrier_ = 0;
  unsigned carrier_mask_[kMaxCarriers] = {};
  Field3 carrier_flux_[kMaxCarriers], carrier_rho_[kMaxCarriers];
  State s_;
  // the mid-step geometry (Options::mid_geometry): the nodes' start-of-step velocities
  Field3 u0_, v0_, w0_;
  bool mid_geometry_ = false;
  // The remap step whose cell volumes (pre_vol, post_vol) a fused launch has written ahead (the
  // corrector the first step's, a step's KE fix the next one's), if any.
  bool volumes_ready_ = false;
  RemapStep volumes_for_{};
  long ke_redone_ = 0;          // sweeps whose dual faces were redone (ke_redo)
  std::vector<double> ledger_;  // this rank's boundary mass ledger (mass_ledger())
  // gamma - 1 of the scene's ideal gas where the free-expansion rule acts (else 0)
  Real expansion_gm1_ = 0;
  bool expanded_ = false;  // whether the current sweep's faces did free-expansion work
  bool expansion_worked();
  void expansion_impulse(int d, const Field3& xw);
  int reflective_face(int d, int s) const;
};

}  // namespace mp::hydro
