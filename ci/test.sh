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
# precision pinned: a build directory once configured for float stays float otherwise. The
# double build builds the executable and every test program (tests_all), not the benchmarks
# (ci/perf-check.sh builds its own; `cmake --build build` builds them all).
MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_BUILD_TARGETS=tests_all bash "${here}/ci/build.sh" \
  -DMINIPAGOSA_PRECISION=double
phase "setup + double build" "${start}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
t0=$(date +%s)
cd "${build}"
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores. The fast
# path: the kinds verification, consistency and unit; not perf (timing verdicts:
# ci/perf-check.sh), pin and long (ci/long.sh, which .ci/run runs after this; README, "Test
# kinds").
ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long|pin'
phase "double suite" "${t0}"
# The single-precision build, so that the float build the README offers keeps building and its
# accuracy claims hold in float: the library and the verification entries' programs, those
# entries run (ci/float.sh verification). .ci/run also runs the rest of the float fast path
# (ci/float.sh rest). MINIPAGOSA_FLOAT=all runs the whole float fast path here, =skip none.
float="${MINIPAGOSA_FLOAT:-verification}"
[ "${MINIPAGOSA_SKIP_FLOAT:-0}" = 1 ] && float=skip
if [ "${float}" != skip ]; then
  t0=$(date +%s)
  MINIPAGOSA_BUILD_DIR="${build}" bash "${here}/ci/float.sh" "${float}"
  phase "float build + ${float} tests" "${t0}"
fi
echo "[test] suite finished in $(( $(date +%s) - start )) s (setup + build + tests; $(IFS=,; echo "${times[*]}" | sed 's/,/, /g'))"
