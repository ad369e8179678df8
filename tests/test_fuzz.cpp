// Deck and command-line fuzzing: well over 100 malformed inputs generated from the real decks in
// configs/ (every numeric value made NaN, infinite, unparseable, out of double range, a list, a
// map, or zero/negative where it must be positive; duplicated and misspelt keys; YAML syntax
// errors; unknown materials, library entries and EOS; binary garbage; a directory as the deck;
// empty and non-map documents) and malformed command lines (bad --set, bad --kokkos-threads,
// unknown options, an output path too long, a missing checkpoint, mesh.ranks against the rank
// count). Each must exit with status 2 (not crash, not hang: 90 s limit), name where the fault
// is (file:line and the key for a deck, the option for a command line), and write nothing.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <regex>
#include <set>

#include "cli_support.hpp"

namespace {

using namespace mp::cli;

struct Case {
  std::string what;                        // printed
  std::string file;                        // deck name written in the test directory ("": none)
  std::string text;                        // its contents
  std::vector<std::string> args;           // command line after the executable
  std::vector<std::string> expect;         // substrings of stderr
  std::vector<std::string> launcher = {};  // e.g. mpiexec -np 2
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string l; std::getline(ss, l);) out.push_back(l);
  return out;
}
std::string join_lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}

// Keys whose value must be positive (zero and negative values are out of range).
const std::set<std::string> kPositive = {"end",        "cfl",     "density", "gamma",
                                         "dt_initial", "dt_max",  "rho0",    "radius",
                                         "log_every",  "samples", "c0",      "growth"};

std::vector<Case> deck_cases() {
  std::vector<Case> cases;
  const std::vector<std::string> decks = {"sod_x.yaml", "sedov.yaml", "water_air.yaml",
                                          "triple_point.yaml", "copper_wall.yaml"};
  // block-style "key: number" lines
  const std::regex numeric(
      R"re(^(\s*(?:- )?)([A-Za-z_0-9]+):\s*([-+]?[0-9][0-9.eE+-]*)\s*(#.*)?$)re");
  const std::vector<std::string> bad = {"nan", ".inf", "abc", "1e400", "[1, 2]", "{a: 1}", "-.inf"};
  int rot = 0;
  for (const auto& deck : decks) {
    const auto base = lines_of(read(config(deck)));
    const std::string stem = deck.substr(0, deck.size() - 5);
    int dups = 0, typos = 0;
    for (std::size_t i = 0; i < base.size(); ++i) {
      std::smatch m;
      if (!std::regex_match(base[i], m, numeric)) continue;
      const std::string key = m[2];
      const int line = static_cast<int>(i) + 1;
      auto mutate = [&](const std::string& value, const std::string& tag) {
        auto l = base;
        l[i] = std::string(m[1]) + key + ": " + value;
        const std::string name = stem + "_" + std::to_string(cases.size()) + ".yaml";
        cases.push_back(
            {deck + ":" + std::to_string(line) + " " + key + " = " + value + " (" + tag + ")",
             name,
             join_lines(l),
             {name},
             {name + ":" + std::to_string(line) + ":", key + "'"}});
      };
      mutate(bad[rot % bad.size()], "bad value");
      ++rot;
      if (kPositive.count(key)) mutate(rot % 2 ? "0" : "-1", "must be positive");
      if (dups < 2) {  // the same key again on the next line
        auto l = base;
        l.insert(l.begin() + static_cast<long>(i) + 1, base[i]);
        const std::string name = stem + "_" + std::to_string(cases.size()) + ".yaml";
        cases.push_back({deck + ":" + std::to_string(line) + " " + key + " given twice",
                         name,
                         join_lines(l),
                         {name},
                         {name + ":" + std::to_string(line + 1) + ":",
                          "given twice, at lines " + std::to_string(line) + " and " +
                              std::to_string(line + 1)}});
        ++dups;
      }
      if (typos < 2) {  // a misspelt key
        auto l = base;
        l[i] = std::string(m[1]) + key + "x: " + std::string(m[3]);
        const std::string name = stem + "_" + std::to_string(cases.size()) + ".yaml";
        cases.push_back({deck + ":" + std::to_string(line) + " key " + key + "x",
                         name,
                         join_lines(l),
                         {name},
                         {name + ":" + std::to_string(line) + ":", "unknown key '" + key + "x'",
                          "did you mean '" + key + "'"}});
        ++typos;
      }
    }
    // YAML syntax errors at a known line: an unclosed list, a stray colon
    for (const auto& [junk, tag] : std::vector<std::pair<std::string, std::string>>{
             {"  cells: [8, 2", "unclosed list"}, {"time: : end", "stray colon"}}) {
      auto l = base;
      const std::size_t at = 7;
      l.insert(l.begin() + static_cast<long>(at), junk);
      const std::string name = stem + "_" + std::to_string(cases.size()) + ".yaml";
      cases.push_back({deck + " YAML syntax error (" + tag + ")",
                       name,
                       join_lines(l),
                       {name},
                       {name + ":", "YAML syntax error"}});
    }
    // unknown material / library / eos names where the deck names one
    for (std::size_t i = 0; i < base.size(); ++i) {
      std::smatch m;
      static const std::regex named(
          R"re(^(\s*(?:- )?)(material|library|eos):\s*([A-Za-z_0-9]+)\s*$)re");
      if (!std::regex_match(base[i], m, named)) continue;
      auto l = base;
      l[i] = std::string(m[1]) + std::string(m[2]) + ": unobtainium";
      const std::string name = stem + "_" + std::to_string(cases.size()) + ".yaml";
      cases.push_back(
          {deck + ":" + std::to_string(i + 1) + " " + std::string(m[2]) + " unobtainium",
           name,
           join_lines(l),
           {name},
           {name + ":" + std::to_string(i + 1) + ":", std::string(m[2]) + "'"}});
      break;  // the first one per deck
    }
  }
  return cases;
}

std::vector<Case> other_cases() {
  std::vector<Case> c;
  const std::string sod = read(config("sod_x.yaml"));
  std::mt19937 rng(20261201);  // fixed seed: the same garbage every run
  for (int n = 0; n < 3; ++n) {
    std::string g(512 + 300 * n, '\0');
    for (auto& ch : g) ch = static_cast<char>(rng() & 0xff);
    const std::string name = "garbage_" + std::to_string(n) + ".yaml";
    c.push_back({"binary garbage " + std::to_string(n), name, g, {name}, {name}});
  }
  c.push_back({"empty deck", "empty.yaml", "", {"empty.yaml"}, {"empty.yaml"}});
  c.push_back({"comment only", "comment.yaml", "# nothing\n", {"comment.yaml"}, {"comment.yaml"}});
  c.push_back(
      {"a scalar document", "scalar.yaml", "hello\n", {"scalar.yaml"}, {"scalar.yaml", "map"}});
  c.push_back({"a list document", "list.yaml", "- a\n- b\n", {"list.yaml"}, {"list.yaml", "map"}});
  c.push_back({"non-scalar key",
               "key.yaml",
               "scene: k\n? [a, b]\n: 1\n",
               {"key.yaml"},
               {"key.yaml:2:", "plain name"}});
  c.push_back({"tab indentation",
               "tab.yaml",
               "scene: t\nmesh:\n\tcells: [8, 2, 2]\n",
               {"tab.yaml"},
               {"tab.yaml:"}});
  c.push_back({"a directory as the deck", "", "", {"."}, {"scene"}});
  c.push_back({"missing deck", "", "", {"nosuch.yaml"}, {"nosuch.yaml"}});
  c.push_back({"empty scene name",
               "s.yaml",
               sod,
               {"s.yaml", "--set", "scene=\"\""},
               {"key 'scene'", "empty"}});
  // command lines
  const std::string deck = config("sod_x.yaml");
  for (const auto& [opt, expect] : std::vector<std::pair<std::string, std::string>>{
           {"--kokkos-threads=0", "--kokkos-threads"},
           {"--kokkos-threads=-3", "--kokkos-threads"},
           {"--kokkos-threads=abc", "--kokkos-threads"},
           {"--kokkos-threads=", "--kokkos-threads"},
           {"--kokkos-threads", "--kokkos-threads"},
           {"--kokkos-threads=99999999999", "--kokkos-threads"},
           {"--frobnicate", "--frobnicate"}}) {
    c.push_back({"option " + opt, "", "", {deck, opt}, {expect}});
  }
  c.push_back(
      {"option --set without a value", "", "", {deck, "--output", "out", "--set"}, {"--set"}});
  for (const auto& [set, expect] : std::vector<std::pair<std::string, std::string>>{
           {"mesh.cells", "key=value"},
           {"mesh.cells=[0,2,2]", "mesh.cells.0"},
           {"mesh.cells=[8,2", "YAML syntax error"},
           {"=3", "key=value"},
           {"mesh..cells=3", "empty key"},
           {"regions.7.density=1", "no element 7"},
           {"time.cfl=nan", "time.cfl"},
           {"mesh.cells=[1048576,1048576,1048576]", "memory"},
           {"materials.0.gamma=1e400", "materials.0.gamma"}}) {
    c.push_back({"--set " + set, "", "", {deck, "--set", set}, {expect}});
  }
  // EOS parameters outside their physical range, named by file:line (a deck) or the option
  std::string stiff = sod;
  const std::string gas = "    eos: ideal_gas\n    gamma: 1.4\n";
  const auto at = stiff.find(gas);
  EXPECT_NE(at, std::string::npos) << "sod_x.yaml changed; update the p_inf case";
  if (at != std::string::npos) {
    stiff.replace(at, gas.size(),
                  "    eos: stiffened_gas\n    params: {gamma: 4.4, p_inf: -0.1}\n");
    // the params line: the line after "eos:"
    const int line = 2 + static_cast<int>(std::count(sod.begin(), sod.begin() + at, '\n'));
    c.push_back({"stiffened gas p_inf < 0 in the deck",
                 "stiff.yaml",
                 stiff,
                 {"stiff.yaml"},
                 {"stiff.yaml:" + std::to_string(line) + ":", "p_inf = -0.1 must be >= 0"}});
  }
  for (const auto& [mat, expect] : std::vector<std::pair<std::string, std::string>>{
           {"{name: gas, eos: jwl, rho0: 1.7, params: {A: 5, B: 0.1, R1: 0, R2: 1, omega: 0.3, "
            "E0: 0.1, D: 0.8, p_cj: 0.3}}",
            "R1 = 0 must be in (0, 1000]"},
           {"{name: gas, eos: mie_gruneisen, rho0: 1, params: {c0: -0.1, s: 1.5, gamma0: 2}}",
            "c0 = -0.1 must be > 0"},
           {"{name: gas, eos: polynomial, rho0: 1, params: {A1: 0, A2: 0, A3: 0, B0: 1, B1: 0}}",
            "A1 = 0 must be > 0"},
           {"{name: gas, library: copper, params: {gamma0: -2}}", "gamma0 = -2 must be in"}}) {
    c.push_back({"EOS out of range: " + expect.substr(0, expect.find(' ')),
                 "",
                 "",
                 {deck, "--set", "materials.0=" + mat},
                 {"--set materials.0=", expect}});
  }
  c.push_back(
      {"output path too long", "", "", {deck, "--output", std::string(5000, 'o')}, {"too long"}});
  c.push_back({"output path component too long",
               "",
               "",
               {deck, "--output", "a/" + std::string(300, 'o')},
               {"component"}});
  c.push_back({"--restart of a missing file",
               "",
               "",
               {deck, "--restart", "nosuch.h5"},
               {"--restart nosuch.h5"}});
  c.push_back({"--restart latest with no checkpoint",
               "",
               "",
               {deck, "--restart", "latest"},
               {"--restart latest", "no checkpoint"}});
  c.push_back({"mesh.ranks [3,1,1] on 2 ranks",
               "",
               "",
               {deck, "--set", "mesh.ranks=[3,1,1]"},
               {"key 'mesh.ranks'", "asks for 3 ranks", "has 2"},
               {"mpiexec", "-np", "2"}});
  c.push_back({"mesh.ranks [2,1,1] on 1 rank",
               "",
               "",
               {deck, "--set", "mesh.ranks=[2,1,1]"},
               {"key 'mesh.ranks'", "has 1"}});
  return c;
}

class Fuzz : public CliTest {};

TEST_F(Fuzz, EveryMalformedInputExits2NamingTheFaultAndWritesNothing) {
  auto cases = deck_cases();
  const auto more = other_cases();
  cases.insert(cases.end(), more.begin(), more.end());
  std::printf("  %zu malformed inputs\n", cases.size());
  EXPECT_GE(cases.size(), 100u);
  // Four children at a time: each spends most of its half second starting MPI, not computing.
  int good = 0;
  const std::size_t batch = 4;
  for (std::size_t b0 = 0; b0 < cases.size(); b0 += batch) {
    const std::size_t b1 = std::min(cases.size(), b0 + batch);
    for (std::size_t n = b0; n < b1; ++n)
      if (!cases[n].file.empty()) write(cases[n].file, cases[n].text);
    const auto before = files(".");
    std::vector<std::unique_ptr<Child>> kids;
    for (std::size_t n = b0; n < b1; ++n) {
      std::vector<std::string> argv = cases[n].launcher;
      argv.push_back(exe());
      std::vector<std::string> a = cases[n].args;
      if (std::find(a.begin(), a.end(), "--output") == a.end())
        a.insert(a.end(), {"--output", "out_" + std::to_string(n)});
      argv.insert(argv.end(), a.begin(), a.end());
      kids.push_back(std::make_unique<Child>(dir_, argv, "_" + std::to_string(n)));
    }
    for (std::size_t n = b0; n < b1; ++n) {
      const Case& c = cases[n];
      // 90 s: a case takes about half a second alone; 30 s tripped once (case 101, 2026-12-05)
      // with a build running beside ctest -j2 on the 2-core host. A hang still fails.
      const Result r = kids[n - b0]->finish(90);
      std::string first = r.err.substr(0, r.err.find('\n'));
      if (first.size() > 150) first = first.substr(0, 150) + "...";
      std::printf("  %3zu %-52.52s exit %d%s  %s\n", n + 1, c.what.c_str(), r.status,
                  r.timed_out ? " (timed out)" : "", first.c_str());
      bool ok = r.status == 2 && !r.timed_out;
      EXPECT_EQ(r.status, 2) << c.what << "\n" << r.err;
      EXPECT_FALSE(r.timed_out) << c.what;
      for (const auto& e : c.expect) {
        const bool has = holds(r.err, e);
        ok = ok && has;
        EXPECT_TRUE(has) << c.what << ": '" << e << "' missing from: " << r.err;
      }
      const auto at = std::find(c.args.begin(), c.args.end(), "--output");
      const std::string out = at == c.args.end() ? "out_" + std::to_string(n) : *(at + 1);
      std::error_code ec;
      const bool wrote = fs::exists(dir_ / out, ec);
      EXPECT_FALSE(wrote) << c.what << ": output written";
      good += ok && !wrote ? 1 : 0;
    }
    // nothing but the decks (and the children's stdout/stderr, removed by finish) is here
    EXPECT_EQ(files("."), before) << "files written by cases " << b0 + 1 << " to " << b1;
    for (std::size_t n = b0; n < b1; ++n)
      if (!cases[n].file.empty()) fs::remove(dir_ / cases[n].file);
  }
  std::printf("  %d of %zu rejected cleanly (exit 2, fault named, nothing written)\n", good,
              cases.size());
}

}  // namespace
