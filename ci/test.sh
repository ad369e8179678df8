#!/usr/bin/env bash
# README command 2: set up, build, and run the test suite with CTest (the fast path in double,
# the verification entries in float; README, "The two commands").
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")"
start=$(date +%s)
phase() {  # name start: the seconds since start, for the closing line
  times+=("$1 $(( $(date +%s) - $2 )) s")
}
times=()
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# Precision pinned: a build directory once configured for float stays float otherwise. The
# double build builds the executable and every test program (tests_all), not the benchmarks
# (ci/perf-check.sh builds its own; `cmake --build build` builds them all).
MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_BUILD_TARGETS=tests_all bash "${here}/ci/build.sh" \
  -DMINIPAGOSA_PRECISION=double
phase "setup + double build" "${start}"
# The single-precision build, so that the float build the README offers keeps building and its
# accuracy claims hold in float: the library and the verification entries' programs, those
# entries run (ci/float.sh verification). .ci/run also runs the rest of the float fast path
# (ci/float.sh rest). MINIPAGOSA_FLOAT=all runs the whole float fast path here, =skip none.
float="${MINIPAGOSA_FLOAT:-verification}"
[ "${MINIPAGOSA_SKIP_FLOAT:-0}" = 1 ] && float=skip
# The float build and its tests run beside the double suite: the suite's tests wait on child
# processes, signals, files and MPI start-up and keep about 1.2 of 2 cores busy on their own,
# so side by side the two keep the cores full (bare 2-core VM, 2026-12-07:
# docs/studies/2026-12-07-build-time.md). Their output goes to build/float.log, shown below.
fpid=""
flog="${build}/float.log"
if [ "${float}" != skip ]; then
  (MINIPAGOSA_BUILD_DIR="${build}" bash "${here}/ci/float.sh" "${float}" build &&
    MINIPAGOSA_BUILD_DIR="${build}" bash "${here}/ci/float.sh" "${float}" test) > "${flog}" 2>&1 &
  fpid=$!
fi
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores. The fast
# path: the kinds verification, consistency and unit; not perf (timing verdicts:
# ci/perf-check.sh), pin and long (ci/long.sh, which .ci/run runs after this; README, "Test
# kinds").
t0=$(date +%s)
suite=0
(cd "${build}" && ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long|pin') ||
  suite=$?
phase "double suite" "${t0}"
if [ -n "${fpid}" ]; then
  t0=$(date +%s)
  fstatus=0
  wait "${fpid}" || fstatus=$?
  if [ "${fstatus}" != 0 ]; then
    cat "${flog}" >&2
    echo "[test] the float build or its ${float} entries failed (log: ${flog})" >&2
    exit 1
  fi
  grep -E '^\[build\]|^\[float\]|tests passed|^Total Test' "${flog}" >&2 || true
  phase "float build + ${float} tests, after the suite" "${t0}"
fi
if [ "${suite}" != 0 ]; then
  echo "[test] the double suite failed" >&2
  exit "${suite}"
fi
echo "[test] suite finished in $(( $(date +%s) - start )) s ($(IFS=,; echo "${times[*]}" | sed 's/,/, /g'))"
