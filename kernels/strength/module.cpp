// The strength module's construction, its fields and their registration (halo, output,
// restart state); its kernels are update.cpp and remap.cpp (module.hpp says what each seam
// does and why).
#include "strength/module.hpp"

#include "strength/halo_parity.hpp"

namespace mp::strength {

Strength::Strength(const Mesh& mesh, const FlowStress& model, Real rho0)
    : mesh_(mesh), model_(model), rho0_(rho0) {
  for (int& q : set_of_) q = -1;
  sets_.push_back(new_set(-1, ""));
  cell_half_ = sets_[0].s_half;
  allocate();
}

Strength::Strength(const Mesh& mesh, const MaterialModels& models, mat::MaterialState* materials,
                   const std::vector<std::string>& names)
    : mesh_(mesh), rho0_(1), models_(models), mm_(materials), names_(names) {
  for (int& q : set_of_) q = -1;
  pooled_ = materials->kind() == mat::LayoutKind::Compact;
  for (int m = 0; m < models.n; ++m) {
    if (models.f[m].kind == kNoStrength) continue;
    set_of_[m] = int(sets_.size());
    if (pooled_) {
      StressSet st;
      st.material = m;
      sets_.push_back(st);
    } else {
      sets_.push_back(new_set(m, "_" + std::to_string(m)));
    }
  }
  const char* comp[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c)
    cell_half_[c] = mesh.new_field(std::string("cell_stress_half_") + comp[c], Centering::Cell);
  if (pooled_) {
    for (int c = 0; c < 6; ++c)
      pure_[c] = mesh.new_field(std::string("pure_stress_") + comp[c], Centering::Cell);
    pure_[6] = mesh.new_field("pure_plastic_strain", Centering::Cell);
    // per slot: the deviator and plastic strain, carried across rebuilds (the half-step
    // deviator of a mixed cell's material lives in half_, indexed by the current pool's slot:
    // no rebuild comes between the predictor that writes it and the corrector that reads it)
    materials->set_extras(7, 7);
    // gather fields: the six of cell_half_ and these, 7 at least (all components of one set)
    for (int q = 6; q < std::max(7, int(sets_.size())); ++q)
      gather_.push_back(mesh.new_field("stress_gather_" + std::to_string(q), Centering::Cell));
  }
  allocate();
}

StressSet Strength::new_set(int material, const std::string& suffix) const {
  const char* comp[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  StressSet st;
  st.material = material;
  for (int c = 0; c < 6; ++c) {
    st.s[c] = mesh_.new_field(std::string("stress_") + comp[c] + suffix, Centering::Cell);
    st.s_half[c] = mesh_.new_field(std::string("stress_half_") + comp[c] + suffix, Centering::Cell);
  }
  st.eps_p = mesh_.new_field("plastic_strain" + suffix, Centering::Cell);
  return st;
}

void Strength::allocate() {
  const Mesh& mesh = mesh_;
  for (int d = 0; d < 3; ++d)
    force_[d] = mesh.new_field(std::string("stress_force_") + "xyz"[d], Centering::Node);
  scratch_ = mesh.new_field("strength_remap_scratch", Centering::Cell);
}

std::vector<unsigned> Strength::carriers() const {
  std::vector<unsigned> c;
  for (const StressSet& st : sets_) c.push_back(st.material < 0 ? 1u : 1u << st.material);
  return c;
}

std::vector<Field3> Strength::carried_fields(int q) const {
  if (pooled_) return {};
  const StressSet& st = sets_[q];
  std::vector<Field3> f(st.s.begin(), st.s.end());
  f.push_back(st.eps_p);
  return f;
}

std::vector<FieldSpec> Strength::fields(unsigned use) const {
  const unsigned uses = kDump | kCheckpoint | (pooled_ ? 0u : unsigned(kHalo));
  std::vector<FieldSpec> f;
  if (!(use & uses)) return f;  // (a pooled set is gathered only for the dumps and checkpoints)
  const char* comp[7] = {"stress_xx", "stress_yy", "stress_zz",     "stress_xy",
                         "stress_yz", "stress_zx", "plastic_strain"};
  for (int q = 0; q < sets(); ++q) {
    const StressSet st = gathered(q);
    const std::string name = st.material < 0                    ? ""
                             : st.material < int(names_.size()) ? "_" + names_[st.material]
                                                                : "_" + std::to_string(st.material);
    const std::string key = st.material < 0 ? "" : "_" + std::to_string(st.material);
    for (int x = 0; x < 7; ++x)
      f.push_back({comp[x] + name,
                   Centering::Cell,
                   x < 6 ? st.s[x] : st.eps_p,
                   uses,
                   comp[x] + key,
                   {{kParity[x][0], kParity[x][1], kParity[x][2]}},
                   x < 6 ? "Mbar" : ""});
  }
  return f;
}

StressSet Strength::gathered(int q) const {
  if (!pooled_) return sets_[q];
  StressSet st;
  st.material = sets_[q].material;
  const char* comp[6] = {"xx", "yy", "zz", "xy", "yz", "zx"};
  for (int c = 0; c < 6; ++c)
    st.s[c] = mesh_.new_field(std::string("stress_") + comp[c], Centering::Cell);
  st.eps_p = mesh_.new_field("plastic_strain", Centering::Cell);
  std::vector<Target> t;
  for (int x = 0; x < 7; ++x) t.push_back({q, x, x < 6 ? st.s[x] : st.eps_p});
  gather(mm_->compact(), t, Where::Block);
  return st;
}

void Strength::restore(const std::vector<FieldSpec>& state) {
  if (!pooled_) return;
  std::vector<Target> t;
  for (int q = 0; q < sets(); ++q)
    for (int x = 0; x < 7; ++x) t.push_back({q, x, state[std::size_t(7 * q + x)].view});
  for (std::size_t a = 0; a < t.size(); a += 16)  // (a scatter takes 16 at most)
    scatter(std::vector<Target>(t.begin() + a, t.begin() + std::min(a + 16, t.size())),
            Where::Owned);
}

}  // namespace mp::strength
