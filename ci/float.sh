#!/usr/bin/env bash
# The single-precision build (tolerances per precision: tests/precision.hpp) and its tests, in
# ./build-float (or ${MINIPAGOSA_BUILD_DIR}-float). One argument, which entries of the fast path:
#   verification  the accuracy claims, each against its float bound (README command 2 runs
#                 this: it builds the library and only the programs those entries run)
#   rest          every other entry but perf and long (unit, consistency, pin), after building
#                 every test program (.ci/run runs this after ci/long.sh)
#   all           both
# A second argument, build or test, does only that half (ci/test.sh builds beside the double
# suite, then tests). The float build has no perf/ programs: timing verdicts and benchmarks run
# in double.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")-float"
which="${1:-verification}"
phase="${2:-both}"
case "${which}" in
  verification) targets=tests_verification select=(-L verification -LE 'perf|long') ;;
  rest) targets=tests_all select=(-LE 'perf|long|verification') ;;
  all) targets=tests_all select=(-LE 'perf|long') ;;
  *) echo "ci/float.sh: unknown argument '${which}' (verification, rest, all)" >&2; exit 2 ;;
esac
case "${phase}" in
  both | build | test) ;;
  *) echo "ci/float.sh: unknown phase '${phase}' (build, test; default both)" >&2; exit 2 ;;
esac
start=$(date +%s)
if [ "${phase}" != test ]; then
  MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_BUILD_TARGETS="${targets}" bash "${here}/ci/build.sh" \
    -DMINIPAGOSA_PRECISION=float -DMINIPAGOSA_ENABLE_PERF=OFF
fi
built=$(date +%s)
if [ "${phase}" != build ]; then
  if [ ! -f "${build}/CTestTestfile.cmake" ]; then
    echo "ci/float.sh: no float build in ${build}; run bash ci/float.sh ${which} build first" >&2
    exit 2
  fi
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  cd "${build}"
  # no perf, no long; the chosen kinds
  ctest --output-on-failure -j "${MINIPAGOSA_CTEST_JOBS:-$(nproc)}" --timeout 900 "${select[@]}"
fi
echo "[float] ${which}: build $(( built - start )) s, tests $(( $(date +%s) - built )) s"
