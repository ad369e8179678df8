// The Sedov octant's L1 density error of a field written by any code, so that another code's
// output (CloverLeaf3D's VTK dumps, read by perf/cloverleaf/side_by_side.py) is measured by the
// same exact solution and norm as minipagosa's (tests/exact/norms.hpp, as perf/tradeoff.cpp):
//
//   sedov_l1 --cells N --length L --time T --density rho.bin
//
// rho.bin: N^3 float64 cell densities of the octant [0, L]^3, x fastest. The blast is
// configs/sedov.yaml's (gamma 1.4, rho0 1, E = alpha so that R = t^(2/5)). Prints one JSON line:
// the L1 error (integral of |rho - rho_exact| over the octant) and R.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "exact/norms.hpp"

int main(int argc, char** argv) {
  CLI::App app{"L1 density error of a Sedov octant against the exact solution"};
  int n = 0;
  double length = 0, t = 0;
  std::string path;
  app.add_option("--cells", n, "cells per axis")->required()->check(CLI::PositiveNumber);
  app.add_option("--length", length, "octant edge")->required()->check(CLI::PositiveNumber);
  app.add_option("--time", t, "time of the field")->required()->check(CLI::PositiveNumber);
  app.add_option("--density", path, "N^3 float64, x fastest")->required();
  CLI11_PARSE(app, argc, argv);
  const std::size_t count = std::size_t(n) * n * n;
  std::vector<double> rho(count);
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(rho.data()), std::streamsize(count * sizeof(double)));
  if (!in || in.peek() != std::ifstream::traits_type::eof()) {
    std::fprintf(stderr, "sedov_l1: %s: expected exactly %zu float64 values\n", path.c_str(),
                 count);
    return 1;
  }
  const double h = length / n, r = std::pow(t, 0.4);
  const double l1 = mp::exact::octant_l1_density(rho, n, h, mp::exact::Sedov(3, 1.4), r);
  std::printf("{\"l1\": %.10g, \"shock_radius\": %.10g}\n", l1, r);
  return 0;
}
