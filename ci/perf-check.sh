#!/usr/bin/env bash
# CI timing regression check (issue #17; docs/perf-check.md), run by .ci/run after the tests:
# build/perf/perf_check times the single-material cycle, the compact and the dense
# multi-material cycles and the halo exchange in interleaved rounds with an in-process STREAM
# triad, compares them with perf/results/perf_baseline.json (each benchmark's threshold set
# from the run-to-run spread measured on this machine) and checks the kernel launches per unit
# exactly. Prints the table, writes build/perf_check.json, exits 1 on a regression.
# The double build only (the float build is not checked); one rank, one OpenMP thread.
#   ci/perf-check.sh                               check against the committed baseline
#   ci/perf-check.sh --update-baseline [--runs N] [--floor F] [--metric M]
#                                                  measure N (default 5) separate runs and
#                                                  write the baseline from them; each threshold
#                                                  is 1 + max(3 x spread, F) (F default 1.0);
#                                                  verdicts on M (default cpu_x_cache: CPU time
#                                                  x the in-cache triad beside it, the steadiest
#                                                  on this shared host; docs/perf-check.md)
# MINIPAGOSA_PERF_INJECT=<benchmark> slows one benchmark on purpose (the check must fail).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")"
baseline="${here}/perf/results/perf_baseline.json"
update=0
runs=5
floor=1.0
metric=cpu_x_cache
while [ $# -gt 0 ]; do
  case "$1" in
    --update-baseline) update=1 ;;
    --runs) runs="$2"; shift ;;
    --floor) floor="$2"; shift ;;
    --metric) metric="$2"; shift ;;
    *) echo "ci/perf-check.sh: unknown argument '$1' (--update-baseline, --runs N, --floor F, --metric M)" >&2; exit 2 ;;
  esac
  shift
done
start=$(date +%s)
if [ ! -f "${build}/CMakeCache.txt" ]; then
  echo "ci/perf-check.sh: no build in ${build}; run ci/build.sh first" >&2
  exit 2
fi
precision=$(sed -n 's/^MINIPAGOSA_PRECISION:[A-Z]*=//p' "${build}/CMakeCache.txt")
if [ "${precision}" != double ]; then
  echo "ci/perf-check.sh: ${build} is a ${precision} build; the check runs on the double build" >&2
  exit 2
fi
cmake --build "${build}" -j "$(nproc)" --target perf_check > /dev/null
# One thread: a block's CPU time is then not lengthened while other processes hold the CPU.
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
exe="${build}/perf/perf_check"
if [ "${update}" = 1 ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "${tmp}"' EXIT
  for i in $(seq 1 "${runs}"); do
    "${exe}" --json "${tmp}/run${i}.json" > "${tmp}/run${i}.txt"
    echo "[perf-check] run ${i} of ${runs}: $(head -n 1 "${tmp}/run${i}.txt" | grep -o 'other processes took [0-9]* %')"
  done
  "${exe}" --make-baseline "${baseline}" --floor "${floor}" --metric "${metric}" "${tmp}"/run*.json
  echo "[perf-check] baseline refreshed in $(( $(date +%s) - start )) s; commit ${baseline#"${here}"/}"
  exit 0
fi
rc=0
# the timing verdicts of the test suite (label perf: perf_check_fires), which ci/test.sh leaves out
(cd "${build}" && ctest --output-on-failure -L perf --timeout 900) || rc=$?
"${exe}" --baseline "${baseline}" --json "${build}/perf_check.json" || rc=$?
echo "[perf-check] finished in $(( $(date +%s) - start )) s (exit ${rc}; results in ${build}/perf_check.json)"
exit "${rc}"
