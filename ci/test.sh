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
# The Debian packages and Kokkos first: both builds below find them there.
bash "${here}/ci/setup.sh" > /dev/null
phase "setup" "${start}"
# The single-precision build, so that the float build the README offers keeps building and its
# accuracy claims hold in float: the library and the verification entries' programs, those
# entries run (ci/float.sh verification). .ci/run also runs the rest of the float fast path
# (ci/float.sh rest). MINIPAGOSA_FLOAT=all runs the whole float fast path here, =skip none.
float="${MINIPAGOSA_FLOAT:-verification}"
[ "${MINIPAGOSA_SKIP_FLOAT:-0}" = 1 ] && float=skip
# It compiles at nice 19 from here on, beside the double build and the double suite, on what
# they leave idle (the double build's links and last files, the suite's waits on child
# processes and MPI start-up) and on the whole machine once they are done; the float tests
# run after both (bare 2-core VM, docs/studies/2026-12-07-build-time.md: 811 s in all, 1.91
# of the 2 cores busy).
fpid=""
mkdir -p "${build}"
flog="${build}/float-build.log"
if [ "${float}" != skip ]; then
  MINIPAGOSA_BUILD_DIR="${build}" nice -n 19 bash "${here}/ci/float.sh" "${float}" build \
    > "${flog}" 2>&1 &
  fpid=$!
fi
# Precision pinned: a build directory once configured for float stays float otherwise. The
# double build builds the executable and every test program (tests_all), not the benchmarks
# (ci/perf-check.sh builds its own; `cmake --build build` builds them all).
t0=$(date +%s)
build_ok=0
MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_BUILD_TARGETS=tests_all bash "${here}/ci/build.sh" \
  -DMINIPAGOSA_PRECISION=double || build_ok=$?
phase "double build" "${t0}"
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores. The fast
# path: the kinds verification, consistency and unit; not perf (timing verdicts:
# ci/perf-check.sh), pin and long (ci/long.sh, which .ci/run runs after this; README, "Test
# kinds").
suite=0
if [ "${build_ok}" = 0 ]; then
  t0=$(date +%s)
  (cd "${build}" && ctest --output-on-failure -j "$(nproc)" --timeout 900 -LE 'perf|long|pin') ||
    suite=$?
  phase "double suite" "${t0}"
fi
if [ -n "${fpid}" ]; then
  t0=$(date +%s)
  if ! wait "${fpid}"; then
    cat "${flog}" >&2
    echo "[test] the float build failed (log: ${flog})" >&2
    exit 1
  fi
  grep -E '^\[build\]|^\[float\]' "${flog}" >&2 || true
  phase "float build, after the suite" "${t0}"
fi
if [ "${build_ok}" != 0 ]; then
  echo "[test] the double build failed" >&2
  exit "${build_ok}"
fi
if [ "${suite}" != 0 ]; then
  echo "[test] the double suite failed" >&2
  exit "${suite}"
fi
if [ -n "${fpid}" ]; then
  t0=$(date +%s)
  # alone on the machine now: one more test than cores keeps them busy while tests wait
  MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_CTEST_JOBS=$(( $(nproc) + 1 )) \
    bash "${here}/ci/float.sh" "${float}" test
  phase "float ${float} tests" "${t0}"
fi
echo "[test] suite finished in $(( $(date +%s) - start )) s ($(IFS=,; echo "${times[*]}" | sed 's/,/, /g'))"
