// Real materials in the hydro: a Mie-Grueneisen solid (or water) striking a rigid wall must
// reach the state the Hugoniot jump conditions give, and material decks fail clearly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "materials/library.hpp"
#include "support.hpp"

using namespace mp;

TEST(Hugoniot, MieGrueneisenMaterialsAgainstARigidWall) {
  const double up = 0.05;  // impact speed, cm/us: the shocked material is at rest on the wall
  for (const char* name : {"copper", "aluminium_6061", "steel_4340", "tungsten", "water"}) {
    const materials::MaterialData* m = materials::find_material(name);
    ASSERT_NE(m, nullptr) << name;
    ASSERT_EQ(m->eos, "mie_gruneisen") << name;
    const double rho0 = m->rho0, c0 = m->param("c0"), s = m->param("s");
    const double us = c0 + s * up;                   // shock speed in the material's frame
    const double p_exact = rho0 * us * up;           // momentum jump
    const double rho_exact = rho0 * us / (us - up);  // mass jump
    const double t = 0.6 * 1.0 / (us - up);          // the shock crosses 60 % of the 1 cm bar
    std::ostringstream ov;
    ov.precision(17);
    ov << "regions.0.density=" << rho0;
    auto r = test::run_scene(test::load_scene(
        "copper_wall.yaml",
        {std::string("materials.0.library=") + name, ov.str(), "time.end=" + std::to_string(t)}));
    ASSERT_TRUE(r.result.ok) << name << ": " << r.result.health.what;
    const Mesh& mesh = r.sim->mesh();
    const auto p = test::gather(mesh, r.sim->hydro().state().p, Centering::Cell);
    const auto rho = test::gather(mesh, r.sim->hydro().state().rho, Centering::Cell);
    const int nx = mesh.global_cells(0);
    const double dx = mesh.dx(0), x_shock = (us - up) * r.result.time;
    // plateau: from 5 cells off the wall (wall heating) to 5 cells behind the shock
    double p_mean = 0, rho_mean = 0, p_dev = 0;
    int n = 0;
    for (int i = 5; (i + 0.5) * dx < x_shock - 5 * dx; ++i, ++n) {
      p_mean += p[i];
      rho_mean += rho[i];
    }
    p_mean /= n;
    rho_mean /= n;
    for (int i = 5; i < 5 + n; ++i) p_dev = std::max(p_dev, std::abs(p[i] / p_exact - 1));
    // shock position: where the pressure crosses half the jump
    double x_num = NAN;
    for (int i = 0; i + 1 < nx; ++i)
      if (p[i] >= 0.5 * p_exact && p[i + 1] < 0.5 * p_exact) {
        x_num = (i + 0.5) * dx + (p[i] - 0.5 * p_exact) / (p[i] - p[i + 1]) * dx;
        break;
      }
    std::printf(
        "%-15s p %.5f Mbar (exact %.5f, %+.2e), rho %.4f (exact %.4f, %+.2e), "
        "max plateau deviation %.2e, shock at %.4f cm (exact %.4f)\n",
        name, p_mean, p_exact, p_mean / p_exact - 1, rho_mean, rho_exact, rho_mean / rho_exact - 1,
        p_dev, x_num, x_shock);
    EXPECT_NEAR(p_mean / p_exact, 1.0, 2e-3) << name;
    EXPECT_NEAR(rho_mean / rho_exact, 1.0, 1e-3) << name;
    // Post-shock ringing: metals stay within 1e-3 of the jump, water (far more compressible at
    // this speed) within 1.4e-2; the plateau mean is within 1.2e-4 for all of them.
    EXPECT_LT(p_dev, 2e-2) << name;
    EXPECT_NEAR(x_num, x_shock, 2 * dx) << name;
  }
}

TEST(MaterialDecks, LibraryNamesAndParametersAreChecked) {
  const std::string base = test::source_dir() + "/configs/copper_wall.yaml";
  auto error_of = [&](const std::vector<std::string>& ov) -> std::string {
    try {
      read_scene(Deck::load(base, ov));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  std::string e = error_of({"materials.0.library=coper"});
  EXPECT_NE(e.find("no material 'coper' in the library; did you mean 'copper'"), std::string::npos)
      << e;
  e = error_of({"materials.0.params={c0: 0.4, gamma: 2}"});
  EXPECT_NE(e.find("unknown key 'gamma'"), std::string::npos) << e;
  e = error_of({"materials.0.params={s: abc}"});
  EXPECT_NE(e.find("key 'materials.0.params.s': expected a number"), std::string::npos) << e;
  e = error_of({"materials.0={name: x, eos: mie_gruneisen, rho0: 8.9, params: {c0: 0.4}}"});
  EXPECT_NE(e.find("needs parameter 's'"), std::string::npos) << e;
  e = error_of({"materials.0={name: x, eos: jwl_products}"});
  EXPECT_NE(e.find("is not one of: ideal_gas, stiffened_gas, mie_gruneisen, polynomial, jwl"),
            std::string::npos)
      << e;
  // An override takes: the library value replaced, the others kept.
  const Scene s = read_scene(Deck::load(base, {"materials.0.params={gamma0: 2.2}"}));
  EXPECT_EQ(s.materials[0].params.at("gamma0"), 2.2);
  EXPECT_EQ(s.materials[0].params.at("c0"), materials::find_material("copper")->param("c0"));
}
