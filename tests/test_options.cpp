// One set of defaults (kernels/hydro/numerics.hpp): a Hydro built from default-constructed
// hydro::Options runs the numerics of a deck that sets none, field for field.
#include <gtest/gtest.h>

#include <cstdio>
#include <tuple>
#include <utility>
#include <vector>

#include "driver/modules.hpp"
#include "support.hpp"

using namespace mp;

namespace {

// A deck that sets no numerics and no step controls: a Noh implosion (the viscosity's two
// terms, the heat flux in the converging shock, the KE fix, the mid-step geometry and the free-
// expansion rule's allocation all act, so any default that differed would show).
const char* const kDefaultDeck = R"(scene: defaults
mesh:
  cells: [16, 16, 16]
  lo: [0, 0, 0]
  hi: [1, 1, 1]
boundaries:
  x: {lo: reflective, hi: outflow}
  y: {lo: reflective, hi: outflow}
  z: {lo: reflective, hi: outflow}
time:
  end: 1.0
  dt_initial: 1.0e-4
materials:
  - name: gas
    eos: ideal_gas
    gamma: 1.6666666666666667
regions:
  - material: gas
    shape: all
    density: 1.0
    pressure: 1.0e-6
    radial_velocity: {speed: -1.0, center: [0, 0, 0]}
)";

bool same(const Field3& a, const Field3& b, const char* name) {
  auto ha = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), a);
  auto hb = Kokkos::create_mirror_view_and_copy(Kokkos::HostSpace(), b);
  long differ = 0;
  for (std::size_t n = 0; n < ha.span(); ++n) differ += ha.data()[n] != hb.data()[n];
  std::printf("  %-4s %ld of %zu values differ\n", name, differ, std::size_t(ha.span()));
  return differ == 0;
}

}  // namespace

TEST(Options, DefaultOptionsRunTheNumericsOfADefaultDeck) {
  RunSettings settings;
  settings.quiet = true;
  Simulation sim(read_scene(Deck::parse(kDefaultDeck, "defaults.yaml")), MPI_COMM_WORLD, settings);
  sim.initialize();
  hydro::Hydro& deck = sim.hydro();

  // the same mesh and EOS, options from hydro::Options{}, the deck's initial state
  Halo halo(sim.mesh());
  hydro::Hydro plain(sim.mesh(), halo, hydro::Options{}, material_eoses(sim.scene()));
  const hydro::State& from = deck.state();
  hydro::State& to = plain.state();
  for (auto [dst, src] : {std::pair{to.rho, from.rho},
                          {to.e, from.e},
                          {to.u, from.u},
                          {to.v, from.v},
                          {to.w, from.w}})
    Kokkos::deep_copy(dst, src);
  plain.prepare();
  EXPECT_EQ(plain.mid_geometry(), deck.mid_geometry());
  EXPECT_EQ(plain.conducts(), deck.conducts());
  EXPECT_EQ(plain.free_expansion_acts(), deck.free_expansion_acts());

  // 10 cycles, each with its own time step, which must agree too (the first grows from the
  // deck's dt_initial, as the driver's does)
  Real dt_deck = Real(sim.scene().time.dt_initial), dt_plain = dt_deck;
  double t = 0;
  for (long cycle = 0; cycle < 10; ++cycle) {
    const hydro::TimeStep a = deck.time_step(dt_deck, t, 1.0);
    const hydro::TimeStep b = plain.time_step(dt_plain, t, 1.0);
    ASSERT_EQ(a.dt, b.dt) << "cycle " << cycle;
    ASSERT_TRUE(deck.step(a.dt, cycle).ok);
    ASSERT_TRUE(plain.step(b.dt, cycle).ok);
    dt_deck = a.dt;
    dt_plain = b.dt;
    t += double(a.dt);
  }
  bool all = true;
  for (auto [a, b, name] : {std::tuple{from.rho, to.rho, "rho"},
                            {from.e, to.e, "e"},
                            {from.p, to.p, "p"},
                            {from.q, to.q, "q"},
                            {from.u, to.u, "u"},
                            {from.v, to.v, "v"},
                            {from.w, to.w, "w"}})
    all = same(a, b, name) && all;
  EXPECT_TRUE(all) << "a Hydro from hydro::Options{} ran other numerics than a default deck";
}
