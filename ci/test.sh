#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite with CTest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")"
start=$(date +%s)
phase() {  # name start: the seconds since start, for the closing line
  times+=("$1 $(( $(date +%s) - $2 )) s")
}
times=()
# precision pinned: a build directory once configured for float stays float otherwise
MINIPAGOSA_BUILD_DIR="${build}" bash "${here}/ci/build.sh" -DMINIPAGOSA_PRECISION=double
phase "setup + double build" "${start}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
t0=$(date +%s)
cd "${build}"
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores. The fast
# path: every kind but perf (timing verdicts run in ci/perf-check.sh) and long (ci/long.sh,
# which .ci/run runs after this; README, "Test kinds").
ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long'
phase "double suite" "${t0}"
# The same fast path in a single-precision build (tolerances per precision: tests/precision.hpp),
# so that the float build the README offers keeps building and passing.
# MINIPAGOSA_SKIP_FLOAT=1 skips it.
if [ "${MINIPAGOSA_SKIP_FLOAT:-0}" != 1 ]; then
  t0=$(date +%s)
  MINIPAGOSA_BUILD_DIR="${build}-float" bash "${here}/ci/build.sh" -DMINIPAGOSA_PRECISION=float
  phase "float build" "${t0}"
  t0=$(date +%s)
  cd "${build}-float"
  ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long'
  phase "float suite" "${t0}"
fi
echo "[test] suite finished in $(( $(date +%s) - start )) s (setup + build + tests; $(IFS=,; echo "${times[*]}" | sed 's/,/, /g'))"
