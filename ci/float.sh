#!/usr/bin/env bash
# The single-precision build (tolerances per precision: tests/precision.hpp) and its tests, in
# ./build-float (or ${MINIPAGOSA_BUILD_DIR}-float). One argument, which entries of the fast path:
#   verification  the accuracy claims, each against its float bound (README command 2 runs
#                 this: it builds the library and only the programs those entries run)
#   rest          every other entry but perf and long (unit, consistency, pin), after building
#                 every test program (.ci/run runs this after ci/long.sh)
#   all           both
# The float build has no perf/ programs: timing verdicts and benchmarks run in double.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")-float"
which="${1:-verification}"
case "${which}" in
  verification) targets=tests_verification select=(-L verification -LE 'perf|long') ;;
  rest) targets=tests_all select=(-LE 'perf|long|verification') ;;
  all) targets=tests_all select=(-LE 'perf|long') ;;
  *) echo "ci/float.sh: unknown argument '${which}' (verification, rest, all)" >&2; exit 2 ;;
esac
start=$(date +%s)
MINIPAGOSA_BUILD_DIR="${build}" MINIPAGOSA_BUILD_TARGETS="${targets}" bash "${here}/ci/build.sh" \
  -DMINIPAGOSA_PRECISION=float -DMINIPAGOSA_ENABLE_PERF=OFF
built=$(date +%s)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "${build}"
# no perf, no long; the chosen kinds
ctest --output-on-failure -j "$(nproc)" --timeout 900 "${select[@]}"
echo "[float] ${which}: build $(( built - start )) s, tests $(( $(date +%s) - built )) s"
