#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite with CTest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")"
start=$(date +%s)
# precision pinned: a build directory once configured for float stays float otherwise
MINIPAGOSA_BUILD_DIR="${build}" bash "${here}/ci/build.sh" -DMINIPAGOSA_PRECISION=double
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "${build}"
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores. Every
# kind but perf (timing verdicts run in ci/perf-check.sh), the long checks included (README,
# "Tests": `ctest -LE 'perf|long'` is the fast path).
ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE perf
# The same suite, less the long checks, in a single-precision build (tolerances per precision:
# tests/precision.hpp), so that the float build the README offers keeps building and passing.
# MINIPAGOSA_SKIP_FLOAT=1 skips it.
if [ "${MINIPAGOSA_SKIP_FLOAT:-0}" != 1 ]; then
  MINIPAGOSA_BUILD_DIR="${build}-float" bash "${here}/ci/build.sh" -DMINIPAGOSA_PRECISION=float
  cd "${build}-float"
  # the fast path: the long checks run in the double build only
  ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long'
fi
echo "[test] suite finished in $(( $(date +%s) - start )) s (setup + build + tests)"
