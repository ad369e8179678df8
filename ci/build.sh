#!/usr/bin/env bash
# Sets up the dependencies (ci/setup.sh) and configures + builds minipagosa in ./build
# (or $MINIPAGOSA_BUILD_DIR; $MINIPAGOSA_BUILD_TARGETS: which targets, default all). Reuses an
# existing build directory; a second run only rebuilds what changed. Extra arguments go to
# CMake (e.g. -DMINIPAGOSA_PRECISION=float).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MINIPAGOSA_BUILD_DIR:-${here}/build}"

kokkos_line=$(bash "${here}/ci/setup.sh" | tail -n 1)
kokkos_root="${kokkos_line#KOKKOS_ROOT=}"

jobs=$(nproc)
# Compiler cache (Debian's ccache, installed by ci/setup.sh): a fresh clone on a machine that
# built minipagosa before compiles only what changed. CCACHE_BASEDIR makes the paths under the
# clone relative, so clones in different directories share entries; an entry is keyed by the
# preprocessed source and the compiler's command line, so a hit is the object a compile would
# give. MINIPAGOSA_NO_CCACHE=1 compiles everything.
want=0 launcher=(-UCMAKE_CXX_COMPILER_LAUNCHER -UCMAKE_C_COMPILER_LAUNCHER)
if [ "${MINIPAGOSA_NO_CCACHE:-0}" != 1 ] && command -v ccache >/dev/null 2>&1; then
  want=1 launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="${here}"
  # this build's own counts (ci/test.sh runs the float build beside the double one)
  mkdir -p "${build}"
  export CCACHE_STATSLOG="$(realpath -m "${build}")/ccache-stats.log"
  rm -f "${CCACHE_STATSLOG}"
fi
have=0
if grep -q '^CMAKE_CXX_COMPILER_LAUNCHER:.*=ccache$' "${build}/CMakeCache.txt" 2>/dev/null; then
  have=1
fi
if [ ! -f "${build}/CMakeCache.txt" ] || [ $# -gt 0 ] || [ "${want}" != "${have}" ]; then
  cmake -S "${here}" -B "${build}" -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="${kokkos_root}" \
    "${launcher[@]}" "$@"
fi
# MINIPAGOSA_BUILD_TARGETS: the targets to build, space-separated (default: all of them), e.g.
# `minipagosa` (README command 1) or `tests_all` (the test programs, ci/test.sh)
targets=()
for t in ${MINIPAGOSA_BUILD_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "${build}" -j "${jobs}" "${targets[@]}"
if [ "${want}" = 1 ]; then
  echo "[build] ccache for this build: $( (ccache --show-log-stats 2>/dev/null || true) |
    grep -E '^ *(Hits|Misses):' | tr -s ' ' | paste -sd ';')" >&2
fi
echo "[build] minipagosa built in ${build} against Kokkos at ${kokkos_root}" >&2
