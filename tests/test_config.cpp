// Strict deck reading: every bad input is an InputError naming file:line, the full key path and
// a specific hint; --set overrides are reported as such; every shipped deck parses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "config/deck.hpp"
#include "config/scene.hpp"
#include "core/error.hpp"
#include "paths.hpp"

namespace {

// A valid deck; the tests replace single lines, so line numbers below refer to this listing.
const std::vector<std::string> kBase = {
    "scene: unit",                                 // 1
    "description: a unit-test deck",               // 2
    "mesh:",                                       // 3
    "  cells: [4, 4, 4]",                          // 4
    "  lo: [0, 0, 0]",                             // 5
    "  hi: [1, 1, 1]",                             // 6
    "boundaries:",                                 // 7
    "  x: reflective",                             // 8
    "  y: periodic",                               // 9
    "  z: {lo: outflow, hi: reflective}",          // 10
    "time:",                                       // 11
    "  end: 0.1",                                  // 12
    "  cfl: 0.5",                                  // 13
    "numerics:",                                   // 14
    "  advection: second",                         // 15
    "  ke_fix: true",                              // 16
    "  viscosity: {linear: 0.2, quadratic: 1.0}",  // 17
    "materials:",                                  // 18
    "  - name: gas",                               // 19
    "    eos: ideal_gas",                          // 20
    "    gamma: 1.4",                              // 21
    "regions:",                                    // 22
    "  - material: gas",                           // 23
    "    shape: all",                              // 24
    "    density: 1.0",                            // 25
    "    pressure: 1.0",                           // 26
    "  - material: gas",                           // 27
    "    shape: box",                              // 28
    "    lo: [0, 0, 0]",                           // 29
    "    hi: [0.5, 1, 1]",                         // 30
    "    density: 2.0",                            // 31
    "    pressure: 2.0",                           // 32
    "  - material: gas",                           // 33
    "    shape: sphere",                           // 34
    "    center: [0.5, 0.5, 0.5]",                 // 35
    "    radius: 0.2",                             // 36
    "    density: 1.0",                            // 37
    "    energy: 3.0",                             // 38
    "output:",                                     // 39
    "  dir: out",                                  // 40
    "  write: false",                              // 41
};

// Line 21 of the base deck with a second (unused) material after it: a multi-material scene.
const char* const kSecondGas = "    gamma: 1.4\n  - name: air\n    eos: ideal_gas\n    gamma: 2";

// The base deck with lines replaced (1-based; "" blanks a line and keeps the numbering).
std::string deck(const std::map<int, std::string>& edits = {}) {
  std::string text;
  for (std::size_t i = 0; i < kBase.size(); ++i) {
    const auto it = edits.find(static_cast<int>(i) + 1);
    text += (it != edits.end() ? it->second : kBase[i]) + "\n";
  }
  return text;
}

// The base deck with lines first..last blanked.
std::string without(int first, int last) {
  std::map<int, std::string> edits;
  for (int l = first; l <= last; ++l) edits[l] = "";
  return deck(edits);
}

// The InputError message read_scene gives; a test failure if there is none.
std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    const mp::Scene s = mp::read_scene(mp::Deck::parse(text, "deck.yaml", overrides));
    ADD_FAILURE() << "no InputError for deck:\n" << text;
  } catch (const mp::InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
  }
  return "";
}

// The message holds every one of `parts` (printed, so a passing run shows what users read).
void expect_holds(const std::string& message, const std::vector<std::string>& parts) {
  std::printf("  %s\n", message.c_str());
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' missing from: " << message;
}

}  // namespace

TEST(Deck, BaseDeckIsValid) {
  const mp::Scene s = mp::read_scene(mp::Deck::parse(deck(), "deck.yaml"));
  EXPECT_EQ(s.name, "unit");
  EXPECT_EQ(s.file, "deck.yaml");
  EXPECT_EQ(s.mesh.cells, (std::array<int, 3>{4, 4, 4}));
  EXPECT_EQ(s.mesh.bc[0][0], mp::BoundaryKind::Reflective);
  EXPECT_EQ(s.mesh.bc[1][1], mp::BoundaryKind::Periodic);
  EXPECT_EQ(s.mesh.bc[2][0], mp::BoundaryKind::Outflow);
  EXPECT_EQ(s.mesh.bc[2][1], mp::BoundaryKind::Reflective);
  EXPECT_EQ(s.time.end, 0.1);
  EXPECT_EQ(s.numerics.advection, mp::hydro::Advection::Second);
  ASSERT_EQ(s.regions.size(), 3u);
  EXPECT_EQ(s.regions[1].shape.kind, "box");
  EXPECT_TRUE(s.regions[1].has_pressure);
  EXPECT_EQ(s.regions[2].shape.kind, "sphere");
  EXPECT_FALSE(s.regions[2].has_pressure);
  EXPECT_EQ(s.regions[2].energy, 3.0);
  EXPECT_FALSE(s.output.write);
}

TEST(Deck, UnknownKeys) {
  expect_holds(error_of(deck({{2, "descripton: x"}})),
               {"deck.yaml:2:", "key 'descripton'", "did you mean 'description'"});
  expect_holds(error_of(deck({{4, "  cels: [4, 4, 4]"}})),
               {"deck.yaml:4:", "key 'mesh.cels'", "did you mean 'cells'"});
  expect_holds(error_of(deck({{17, "  viscosity: {linear: 0.2, quadratc: 1.0}"}})),
               {"deck.yaml:17:", "key 'numerics.viscosity.quadratc'", "did you mean 'quadratic'"});
  expect_holds(error_of(deck({{25, "    densty: 1.0"}})),
               {"deck.yaml:25:", "key 'regions.0.densty'", "did you mean 'density'"});
  expect_holds(error_of(deck({{37, "    dens: 1.0"}})),
               {"deck.yaml:37:", "key 'regions.2.dens'", "did you mean 'density'"});
  expect_holds(error_of(deck({{21, "    gama: 1.4"}})),
               {"deck.yaml:21:", "key 'materials.0.gama'", "did you mean 'gamma'"});
  expect_holds(error_of(deck({{41, "  writ: false"}})),
               {"deck.yaml:41:", "key 'output.writ'", "did you mean 'write'"});
}

TEST(Deck, WrongTypes) {
  expect_holds(error_of(deck({{13, "  cfl: fast"}})),
               {"deck.yaml:13:", "key 'time.cfl'", "expected a number, got 'fast'"});
  expect_holds(error_of(deck({{6, "  hi: [1, 1]"}})),
               {"deck.yaml:6:", "key 'mesh.hi'", "expected a list of 3 numbers"});
  expect_holds(error_of(deck({{4, "  cells: [4, 4]"}})),
               {"deck.yaml:4:", "key 'mesh.cells'", "expected a list of 3 integers"});
  expect_holds(error_of(deck({{4, "  cells: [4, 4.5, 4]"}})),
               {"deck.yaml:4:", "key 'mesh.cells.1'", "expected an integer, got '4.5'"});
  expect_holds(
      error_of(deck({{16, "  ke_fix: yes please"}})),
      {"deck.yaml:16:", "key 'numerics.ke_fix'", "expected true or false, got 'yes please'"});
  expect_holds(error_of(deck({{12, "  end: [1, 2]"}})),
               {"deck.yaml:12:", "key 'time.end'", "expected a number"});
  expect_holds(error_of(deck({{3, "mesh: 4"}, {4, ""}, {5, ""}, {6, ""}})),
               {"deck.yaml:3:", "key 'mesh'", "expected a map"});
  expect_holds(error_of(deck({{1, "scene: bad name!"}})),
               {"deck.yaml:1:", "key 'scene'", "only letters, digits"});
}

TEST(Deck, OutOfRange) {
  expect_holds(error_of(deck({{13, "  cfl: 1.5"}})),
               {"deck.yaml:13:", "key 'time.cfl'", "value 1.5 is out of range [0.001, 1]"});
  expect_holds(error_of(deck({{25, "    density: -1"}})),
               {"deck.yaml:25:", "key 'regions.0.density'", "value -1 is out of range"});
  expect_holds(error_of(deck({{31, "    density: 0"}})),
               {"deck.yaml:31:", "key 'regions.1.density'", "density must be positive"});
  expect_holds(error_of(deck({{21, "    gamma: 0.5"}})),
               {"deck.yaml:21:", "key 'materials.0.gamma'", "value 0.5 is out of range"});
  expect_holds(error_of(deck({{4, "  cells: [0, 4, 4]"}})),
               {"deck.yaml:4:", "key 'mesh.cells.0'", "value 0 is out of range [1, "});
  expect_holds(error_of(deck({{12, "  end: 0"}})),
               {"deck.yaml:12:", "key 'time.end'", "end time must be positive"});
  expect_holds(error_of(deck({{12, "  end: .inf"}})),
               {"deck.yaml:12:", "key 'time.end'", "expected a finite number"});
  expect_holds(error_of(deck({{36, "    radius: 0"}})),
               {"deck.yaml:36:", "key 'regions.2.radius'", "sphere radius must be positive"});
}

TEST(Deck, EnumerationErrors) {
  expect_holds(error_of(deck({{15, "  advection: thrid"}})),
               {"deck.yaml:15:", "key 'numerics.advection'",
                "'thrid' is not one of: second, first, third", "did you mean 'third'"});
  expect_holds(
      error_of(deck({{8, "  x: reflect"}})),
      {"deck.yaml:8:", "key 'boundaries.x'",
       "'reflect' is not one of: reflective, outflow, periodic", "did you mean 'reflective'"});
  expect_holds(error_of(deck({{10, "  z: {lo: outflow, hi: periodc}"}})),
               {"deck.yaml:10:", "key 'boundaries.z.hi'", "did you mean 'periodic'"});
  expect_holds(
      error_of(deck({{16, "  ke_fix_share: by_mass"}})),
      {"deck.yaml:16:", "key 'numerics.ke_fix_share'", "'by_mass' is not one of: mass, equal"});
  EXPECT_EQ(mp::read_scene(mp::Deck::parse(deck(), "deck.yaml")).numerics.ke_fix_share,
            mp::hydro::KeFixShare::Mass);
  EXPECT_EQ(mp::read_scene(mp::Deck::parse(deck({{16, "  ke_fix_share: equal"}, {21, kSecondGas}}),
                                           "deck.yaml"))
                .numerics.ke_fix_share,
            mp::hydro::KeFixShare::Equal);
  expect_holds(error_of(deck({{20, "    eos: ideal"}})),
               {"deck.yaml:20:", "key 'materials.0.eos'", "'ideal' is not one of: ideal_gas"});
  expect_holds(error_of(deck({{28, "    shape: cube"}})),
               {"deck.yaml:28:", "key 'regions.1.shape'", "not one of: all, box, sphere"});
}

TEST(Deck, ImpossibleGeometry) {
  expect_holds(error_of(deck({{6, "  hi: [1, 0, 1]"}})),
               {"deck.yaml:6:", "key 'mesh.hi'", "must exceed the lower corner along y"});
  expect_holds(error_of(deck({{30, "    hi: [0.5, 1, 0]"}})),
               {"deck.yaml:30:", "key 'regions.1.hi'", "must exceed its lower corner along z"});
  expect_holds(error_of(deck({{29, "    lo: [2, 0, 0]"}, {30, "    hi: [3, 1, 1]"}})),
               {"deck.yaml:29:", "key 'regions.1.lo'", "box lies outside the mesh"});
  expect_holds(error_of(deck({{35, "    center: [5, 5, 5]"}})),
               {"deck.yaml:35:", "key 'regions.2.center'", "sphere lies outside the mesh"});
  expect_holds(error_of(deck({{10, "  z: {lo: periodic, hi: reflective}"}})),
               {"deck.yaml:10:", "key 'boundaries.z'", "periodic must be set on both faces"});
}

TEST(Deck, MissingRequiredKeys) {
  expect_holds(error_of(without(3, 6)), {"deck.yaml:1:", "key 'mesh'", "missing required key"});
  expect_holds(error_of(without(12, 12)),
               {"deck.yaml:13:", "key 'time.end'", "missing required key 'end'"});
  expect_holds(error_of(without(11, 13)), {"deck.yaml:1:", "key 'time'", "missing required"});
  expect_holds(error_of(without(18, 21)), {"deck.yaml:1:", "key 'materials'", "missing required"});
  expect_holds(error_of(without(22, 38)), {"deck.yaml:1:", "key 'regions'", "missing required"});
  expect_holds(error_of(deck({{4, ""}})),
               {"deck.yaml:5:", "key 'mesh'", "missing required key 'cells'", "or 'zone'"});
  std::map<int, std::string> empty_regions{{22, "regions: []"}};
  for (int l = 23; l <= 38; ++l) empty_regions[l] = "";
  expect_holds(error_of(deck(empty_regions)),
               {"deck.yaml:22:", "key 'regions'", "expected a non-empty list of regions"});
  expect_holds(error_of(deck({{24, "    shape: box\n    lo: [0, 0, 0]\n    hi: [1, 1, 1]"}})),
               {"deck.yaml:23:", "key 'regions.0'", "the first region must be 'shape: all'"});
  expect_holds(error_of(deck({{26, ""}})),
               {"deck.yaml:23:", "key 'regions.0'", "exactly one of 'pressure' or 'energy'"});
}

// mesh.zone: one cell size instead of cells per axis; cells = round((hi - lo) / zone), >= 1.
TEST(Deck, ZoneSize) {
  // extents 1, 0.8, 0.6 at zone 0.3: 3.33 -> 3, 2.67 -> 3, 2 -> 2
  const mp::Scene s = mp::read_scene(
      mp::Deck::parse(deck({{4, "  zone: 0.3"}, {6, "  hi: [1, 0.8, 0.6]"}}), "deck.yaml"));
  std::printf("zone 0.3 over [1, 0.8, 0.6]: cells %d %d %d\n", s.mesh.cells[0], s.mesh.cells[1],
              s.mesh.cells[2]);
  EXPECT_EQ(s.mesh.cells, (std::array<int, 3>{3, 3, 2}));
  // a zone wider than the mesh: round(1 / 3) = 0, raised to the floor of one cell
  const mp::Scene wide = mp::read_scene(mp::Deck::parse(deck({{4, "  zone: 3"}}), "deck.yaml"));
  EXPECT_EQ(wide.mesh.cells, (std::array<int, 3>{1, 1, 1}));
  // 0.25 divides the unit cube exactly: 4 per axis, the base deck's cells
  const mp::Scene exact = mp::read_scene(mp::Deck::parse(deck({{4, "  zone: 0.25"}}), "deck.yaml"));
  EXPECT_EQ(exact.mesh.cells, (std::array<int, 3>{4, 4, 4}));
  // a --set override of one replaces the other given in the file
  const mp::Scene set_cells = mp::read_scene(
      mp::Deck::parse(deck({{4, "  zone: 0.25"}}), "deck.yaml", {"mesh.cells=[2,3,5]"}));
  EXPECT_EQ(set_cells.mesh.cells, (std::array<int, 3>{2, 3, 5}));
  const mp::Scene set_zone =
      mp::read_scene(mp::Deck::parse(deck(), "deck.yaml", {"mesh.zone=0.5"}));
  EXPECT_EQ(set_zone.mesh.cells, (std::array<int, 3>{2, 2, 2}));

  expect_holds(error_of(deck({{4, "  cells: [4, 4, 4]\n  zone: 0.25"}})),
               {"deck.yaml:4:", "key 'mesh'", "exactly one of 'cells'", "or 'zone'", "not both"});
  expect_holds(error_of(deck({{4, ""}})),
               {"deck.yaml:5:", "key 'mesh'", "missing required key 'cells'", "or 'zone'"});
  expect_holds(error_of(deck({{4, "  zone: 0"}})),
               {"deck.yaml:4:", "key 'mesh.zone'", "the zone size must be positive"});
  expect_holds(error_of(deck({{4, "  zone: -0.1"}})),
               {"deck.yaml:4:", "key 'mesh.zone'", "the zone size must be positive"});
  expect_holds(error_of(deck({{4, "  zone: fine"}})),
               {"deck.yaml:4:", "key 'mesh.zone'", "expected a number, got 'fine'"});
  // 1 / 1e-7 = 1e7 cells per axis, beyond the 2^20 a cells list may give
  expect_holds(error_of(deck({{4, "  zone: 1.0e-7"}})),
               {"deck.yaml:4:", "key 'mesh.zone'", "more than 2^20 cells along x"});
  expect_holds(error_of(deck({{4, "  zone: 0.25"}}), {"mesh.zone=-1"}),
               {"--set mesh.zone=-1", "key 'mesh.zone'", "the zone size must be positive"});
}

TEST(Deck, MaterialsAndRegions) {
  expect_holds(error_of(deck({{27, "  - material: gaz"}})),
               {"deck.yaml:27:", "key 'regions.1.material'", "unknown material 'gaz'",
                "did you mean 'gas'"});
  expect_holds(error_of(deck({{26, "    pressure: 1.0\n    energy: 2.0"}})),
               {"deck.yaml:23:", "key 'regions.0'", "exactly one of 'pressure' or 'energy'"});
  expect_holds(
      error_of(deck({{21, "    gamma: 1.4\n  - name: gas\n    eos: ideal_gas\n    gamma: 2"}})),
      {"deck.yaml:22:", "key 'materials.1.name'", "defined twice"});
  // two materials are a multi-material scene: the unsplit remap is refused there, by line
  expect_holds(
      error_of(deck({{16, "  ke_fix: true\n  remap: unsplit"},
                     {21, "    gamma: 1.4\n  - name: air\n    eos: ideal_gas\n    gamma: 2"}})),
      {"deck.yaml:17:", "key 'numerics.remap'", "single-material scenes only"});
  expect_holds(
      error_of(deck({{16, "  layout: sparse"}})),
      {"deck.yaml:16:", "key 'numerics.layout'", "'sparse' is not one of: compact, dense"});
  expect_holds(error_of(deck({{16, "  interface: plic"}})),
               {"deck.yaml:16:", "key 'numerics.interface'", "youngs, elvira, slic, none"});
  expect_holds(error_of(deck({{16, "  min_fraction: 0.5"}})),
               {"deck.yaml:16:", "key 'numerics.min_fraction'"});
  expect_holds(error_of(deck({{16, "  closure: equilibrium"}})),
               {"deck.yaml:16:", "key 'numerics.closure'",
                "'equilibrium' is not one of: equal_strain, relaxation"});
  expect_holds(error_of(deck({{16, "  relaxation_iterations: 0"}})),
               {"deck.yaml:16:", "key 'numerics.relaxation_iterations'", "out of range"});
  expect_holds(error_of(deck({{16, "  relaxation_iterations: many"}})),
               {"deck.yaml:16:", "key 'numerics.relaxation_iterations'"});
  expect_holds(error_of(deck({{16, "  solid_floor: 1.5"}})),
               {"deck.yaml:16:", "key 'numerics.solid_floor'", "out of range"});
  expect_holds(error_of(deck({{16, "  solid_floor: -0.1"}})),
               {"deck.yaml:16:", "key 'numerics.solid_floor'", "out of range"});
  expect_holds(error_of(deck({{16, "  void_density: -1e-6"}})),
               {"deck.yaml:16:", "key 'numerics.void_density'", "out of range"});
  expect_holds(error_of(deck({{16, "  void_density: thin"}})),
               {"deck.yaml:16:", "key 'numerics.void_density'"});
  EXPECT_EQ(mp::read_scene(mp::Deck::parse(deck(), "deck.yaml")).numerics.void_density, 0.0);
  EXPECT_EQ(mp::read_scene(mp::Deck::parse(deck({{16, "  void_density: 1.0e-6"}}), "deck.yaml"))
                .numerics.void_density,
            1e-6);
  // the tension cutoff is a floor on tension: zero or below, a finite number
  expect_holds(
      error_of(deck({{21, "    gamma: 1.4\n    p_min: 1.0e-3"}})),
      {"deck.yaml:22:", "key 'materials.0.p_min'", "value 1.0e-3 is out of range [-1000, 0]"});
  expect_holds(error_of(deck({{21, "    gamma: 1.4\n    p_min: strong"}})),
               {"deck.yaml:22:", "key 'materials.0.p_min'"});
  expect_holds(error_of(deck({{21, "    gamma: 1.4\n    p_min: -.inf"}})),
               {"deck.yaml:22:", "key 'materials.0.p_min'", "expected a finite number"});
  const mp::Scene cut = mp::read_scene(
      mp::Deck::parse(deck({{21, "    gamma: 1.4\n    p_min: -2.5e-3"}}), "deck.yaml"));
  EXPECT_TRUE(cut.materials[0].has_p_min);
  EXPECT_EQ(cut.materials[0].p_min, -2.5e-3);
  EXPECT_FALSE(mp::read_scene(mp::Deck::parse(deck(), "deck.yaml")).materials[0].has_p_min);
}

// An option that applies to the other kind of scene is refused with file:line and key (config/
// options.hpp, numerics_scopes): the hydro would ignore it, and the run would not be the one
// the deck describes.
TEST(Deck, OptionsOfTheOtherKindOfSceneAreRefused) {
  // single-material options on a two-material scene
  for (const char* line :
       {"  heat_flux: 8", "  geometry: fixed", "  free_expansion: 0.5", "  ke_fix_redo: false"}) {
    const std::string key = std::string(line).substr(2, std::string(line).find(':') - 2);
    expect_holds(error_of(deck({{16, line}, {21, kSecondGas}})),
                 {"deck.yaml:16:", "key 'numerics." + key + "'",
                  "applies to single-material scenes only", "this scene has 2 materials"});
    // on one material the same line is read
    EXPECT_NO_THROW(mp::read_scene(mp::Deck::parse(deck({{16, line}}), "deck.yaml"))) << line;
  }
  // multi-material options on a one-material scene
  for (const char* line :
       {"  layout: dense", "  interface: slic", "  closure: relaxation", "  ke_fix_share: equal",
        "  min_fraction: 1e-10", "  relaxation_iterations: 5", "  solid_floor: 0.5"}) {
    const std::string key = std::string(line).substr(2, std::string(line).find(':') - 2);
    expect_holds(error_of(deck({{16, line}})),
                 {"deck.yaml:16:", "key 'numerics." + key + "'",
                  "applies to multi-material scenes only", "this scene has one material"});
    EXPECT_NO_THROW(
        mp::read_scene(mp::Deck::parse(deck({{16, line}, {21, kSecondGas}}), "deck.yaml")))
        << line;
  }
  // the same from the command line names the --set
  expect_holds(error_of(deck(), {"numerics.layout=dense"}),
               {"--set numerics.layout=dense", "applies to multi-material scenes only"});
  expect_holds(error_of(deck({{21, kSecondGas}}), {"numerics.geometry=fixed"}),
               {"--set numerics.geometry=fixed", "applies to single-material scenes only"});
  // options of every scene stay accepted on both
  for (const char* line : {"  ke_fix: false", "  samples: 2", "  void_density: 1e-6"}) {
    EXPECT_NO_THROW(mp::read_scene(mp::Deck::parse(deck({{16, line}}), "deck.yaml"))) << line;
    EXPECT_NO_THROW(
        mp::read_scene(mp::Deck::parse(deck({{16, line}, {21, kSecondGas}}), "deck.yaml")))
        << line;
  }
}

TEST(Deck, YamlSyntaxError) {
  std::string m = error_of(deck({{9, "  y: [periodic"}}));
  expect_holds(m, {"deck.yaml:", "YAML syntax error"});
  m = error_of(deck({{13, "  cfl: 0.5: 2"}}));
  expect_holds(m, {"deck.yaml:13:", "YAML syntax error"});
  m = error_of(deck({{16, "   ke_fix: true"}}));
  expect_holds(m, {"deck.yaml:16:", "YAML syntax error"});
  expect_holds(error_of("- just\n- a list\n"), {"deck.yaml", "must be a YAML map"});
}

TEST(Deck, OverrideErrors) {
  std::string m = error_of(deck(), {"mesh.cells=[0,8,8]"});
  expect_holds(m, {"--set mesh.cells=[0,8,8]", "key 'mesh.cells.0'", "out of range"});
  EXPECT_EQ(m.find("deck.yaml"), std::string::npos) << m;
  expect_holds(error_of(deck(), {"mesh.cells=[8,8]"}),
               {"--set mesh.cells=[8,8]", "key 'mesh.cells'", "expected a list of 3 integers"});
  expect_holds(error_of(deck(), {"time.cfl=2"}), {"--set time.cfl=2", "key 'time.cfl'", "range"});
  expect_holds(error_of(deck(), {"numerics.advection=thrid"}),
               {"--set numerics.advection=thrid", "second, first"});
  // an unknown key given only on the command line
  expect_holds(error_of(deck(), {"mesh.cels=[8,8,8]"}),
               {"--set mesh.cels=[8,8,8]", "key 'mesh.cels'", "did you mean 'cells'"});
  expect_holds(error_of(deck(), {"tim.end=1"}),
               {"--set tim.end=1", "key 'tim'", "did you mean 'time'"});
  expect_holds(
      error_of(deck(), {"numerics.viscosty.linear=1"}),
      {"--set numerics.viscosty.linear=1", "key 'numerics.viscosty'", "did you mean 'viscosity'"});
  // malformed overrides
  expect_holds(error_of(deck(), {"mesh.cells"}), {"--set mesh.cells", "expected key=value"});
  expect_holds(error_of(deck(), {"=3"}), {"--set =3", "expected key=value"});
  expect_holds(error_of(deck(), {"mesh..cells=3"}), {"--set mesh..cells=3", "empty key"});
  expect_holds(error_of(deck(), {"regions.7.density=2"}),
               {"--set regions.7.density=2", "no element 7"});
  expect_holds(error_of(deck(), {"mesh.cells=[1,2"}), {"--set mesh.cells=[1,2", "YAML syntax"});
  expect_holds(error_of(deck(), {"regions.first.density=1"}),
               {"--set regions.first.density=1", "not inside a map"});
  // a scalar overridden by a map is then the wrong type, reported against the override
  expect_holds(error_of(deck(), {"scene.x=1"}),
               {"--set scene.x=1", "key 'scene'", "expected a string"});
}

TEST(Deck, OverridesChangeValues) {
  const mp::Scene s = mp::read_scene(mp::Deck::parse(
      deck(), "deck.yaml",
      {"mesh.cells=[8,8,8]", "regions.1.density=2.5", "numerics.advection=first", "time.end=0.02",
       "numerics.viscosity.linear=0", "output.write=true", "boundaries.x=outflow"}));
  EXPECT_EQ(s.mesh.cells, (std::array<int, 3>{8, 8, 8}));
  EXPECT_EQ(s.regions[1].density, 2.5);
  EXPECT_EQ(s.numerics.advection, mp::hydro::Advection::First);
  EXPECT_EQ(s.time.end, 0.02);
  EXPECT_EQ(s.numerics.q_linear, 0.0);
  EXPECT_EQ(s.numerics.q_quadratic, 1.0);
  EXPECT_TRUE(s.output.write);
  EXPECT_EQ(s.mesh.bc[0][0], mp::BoundaryKind::Outflow);
  // an override may add a key the deck leaves out
  const mp::Scene t =
      mp::read_scene(mp::Deck::parse(without(14, 17), "deck.yaml", {"numerics.advection=first"}));
  EXPECT_EQ(t.numerics.advection, mp::hydro::Advection::First);
  const mp::Scene u =
      mp::read_scene(mp::Deck::parse(deck(), "deck.yaml", {"numerics.advection=third"}));
  EXPECT_EQ(u.numerics.advection, mp::hydro::Advection::Third);
  EXPECT_EQ(mp::hydro::advection_order(u.numerics.advection), 3);
}

TEST(Deck, EditDistanceAndNearest) {
  EXPECT_EQ(mp::edit_distance("", ""), 0);
  EXPECT_EQ(mp::edit_distance("", "abc"), 3);
  EXPECT_EQ(mp::edit_distance("abc", ""), 3);
  EXPECT_EQ(mp::edit_distance("cells", "cells"), 0);
  EXPECT_EQ(mp::edit_distance("cels", "cells"), 1);
  EXPECT_EQ(mp::edit_distance("kitten", "sitting"), 3);
  EXPECT_EQ(mp::edit_distance("thrid", "third"), 2);
  EXPECT_EQ(mp::edit_distance("abc", "cba"), mp::edit_distance("cba", "abc"));
  EXPECT_EQ(mp::nearest("cels", {"cells", "lo", "hi", "ranks"}), "cells");
  EXPECT_EQ(mp::nearest("reflect", {"reflective", "outflow", "periodic"}), "reflective");
  EXPECT_EQ(mp::nearest("gaz", {"gas", "air"}), "gas");
  EXPECT_EQ(mp::nearest("x", {}), "");
}

// A region's wave block: the profile and the axis (tests/test_hydro.cpp's convergence runs).
TEST(Deck, WaveShapeAndDiagonal) {
  const std::string with_wave = deck({{26, "    pressure: 1.0\n    wave: {amplitude: 0.2}"}});
  const mp::Scene a = mp::read_scene(mp::Deck::parse(
      with_wave, "deck.yaml", {"regions.0.wave.shape=plateau", "regions.0.wave.axis=diagonal"}));
  EXPECT_EQ(a.regions[0].wave_shape, 1);
  EXPECT_EQ(a.regions[0].wave_axis, 3);
  expect_holds(error_of(with_wave, {"regions.0.wave.shape=plato"}),
               {"key 'regions.0.wave.shape'", "'plato' is not one of: sine, plateau"});
  expect_holds(error_of(with_wave, {"regions.0.wave.axis=diagonal", "mesh.cells=[8,4,4]"}),
               {"key 'regions.0.wave.axis'", "same number of cells along every axis"});
}

TEST(Deck, ShippedDecksParse) {
  const std::string dir = mp::test::source_dir() + "/configs";
  const std::vector<std::string> files = mp::test::shipped_decks();
  ASSERT_FALSE(files.empty()) << "no decks in " << dir;
  // every shipped deck, by name: a deck deleted or renamed fails here (the README's scenes table
  // lists them)
  const std::vector<std::string> expected = {
      "charge_3d",    "copper_wall", "elastic_wave", "fragment_3d",  "leblanc", "mader",
      "noh",          "noh_planar",  "perforator",   "products_air", "sedov",   "shock_initiation",
      "smooth_wave",  "sod2",        "sod_x",        "sod_y",        "sod_z",   "sphere_advection",
      "taylor_anvil", "test123",     "triple_point", "water_air"};
  std::vector<std::string> found;
  for (const auto& f : files) found.push_back(f.substr(dir.size() + 1, f.size() - dir.size() - 6));
  std::printf("%zu decks in %s\n", found.size(), dir.c_str());
  EXPECT_EQ(found, expected);
  for (const auto& f : files) {
    SCOPED_TRACE(f);
    try {
      const mp::Scene s = mp::read_scene(mp::Deck::load(f));
      std::printf("  %-22s scene '%s', %zu materials, %zu regions, end %g\n",
                  f.substr(dir.size() + 1).c_str(), s.name.c_str(), s.materials.size(),
                  s.regions.size(), s.time.end);
      EXPECT_FALSE(s.name.empty());
      EXPECT_GT(s.time.end, 0.0);
      EXPECT_FALSE(s.regions.empty());
      EXPECT_EQ(s.regions[0].shape.kind, "all");
      // and the usual test-size overrides apply to each of them (16 cells: at 8 the Sedov
      // deposit sphere would hold no cell centre, which is rightly an input error)
      const mp::Scene small =
          mp::read_scene(mp::Deck::load(f, {"mesh.cells=[16,16,16]", "numerics.advection=first"}));
      EXPECT_EQ(small.mesh.cells, (std::array<int, 3>{16, 16, 16}));
      EXPECT_EQ(small.numerics.advection, mp::hydro::Advection::First);
    } catch (const mp::InputError& e) {
      ADD_FAILURE() << e.what();
    }
  }
}

TEST(Deck, MissingFile) {
  try {
    mp::Deck::load("/nonexistent/dir/deck.yaml");
    ADD_FAILURE() << "no InputError";
  } catch (const mp::InputError& e) {
    expect_holds(e.what(), {"/nonexistent/dir/deck.yaml", "cannot open"});
  }
}
