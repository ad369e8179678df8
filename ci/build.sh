#!/usr/bin/env bash
# Sets up the dependencies (ci/setup.sh) and configures + builds minipagosa in ./build
# (or $MINIPAGOSA_BUILD_DIR). Reuses an existing build directory; a second run only rebuilds
# what changed. Extra arguments go to CMake (e.g. -DMINIPAGOSA_PRECISION=float).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MINIPAGOSA_BUILD_DIR:-${here}/build}"

kokkos_line=$(bash "${here}/ci/setup.sh" | tail -n 1)
kokkos_root="${kokkos_line#KOKKOS_ROOT=}"

jobs=$(nproc)
if [ ! -f "${build}/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  cmake -S "${here}" -B "${build}" -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="${kokkos_root}" "$@"
fi
cmake --build "${build}" -j "${jobs}"
echo "[build] minipagosa built in ${build} against Kokkos at ${kokkos_root}" >&2
