#!/usr/bin/env bash
# CTest test perf_check_fires (label perf): the timing check fires on an injected slowdown and
# passes a plain rerun. It records its own baseline in a temporary directory (two quick runs,
# their medians averaged; verdicts on cpu_x_cache, as ci/perf-check.sh's baseline), then runs
# the check twice against it with threshold 2.0 for every
# benchmark, the committed baseline's (its floor 1.0; docs/perf-check.md). Not less: the host
# is a VM shared with other machines, and its speed moves under a run whatever this VM does
# (over 5 quick runs the CPU-time medians spread by 4-11 %, but the CI run of af8c2c0 ran the
# plain rerun 1.34 / 1.62 / 1.55 / 1.78x slower than the baseline recorded a minute before in
# the same test, nothing else running in the VM and the triad unchanged, and failed at 1.5):
#   plain                                   exit 0, "perf_check: passed"
#   MINIPAGOSA_PERF_INJECT=single_material  exit 1, the single_material row "SLOWER: REGRESSION"
#   MINIPAGOSA_PERF_INJECT_REPEATS=50       (50 more lagrange::viscosity calls per 16^3 cycle:
#                                           about 3.5 times the cycle's time), no other row
#                                           slower, and exactly 50 more launches named (35 -> 85 today).
#   perf_check_test.sh PERF_CHECK_EXE
set -uo pipefail
exe="$1"
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
unset MINIPAGOSA_PERF_INJECT MINIPAGOSA_PERF_INJECT_REPEATS
fail=0
check() {  # what, condition...
  local what="$1"
  shift
  if "$@"; then echo "ok: ${what}"; else echo "FAILED: ${what}"; fail=1; fi
}

for i in 1 2; do
  "${exe}" --quick --json "${tmp}/run${i}.json" > "${tmp}/record${i}.txt" 2>&1
  check "recording run ${i} exits 0" test $? -eq 0
done
"${exe}" --make-baseline "${tmp}/baseline.json" --metric cpu_x_cache "${tmp}/run1.json" "${tmp}/run2.json"
check "baseline written" test -s "${tmp}/baseline.json"

"${exe}" --quick --baseline "${tmp}/baseline.json" --threshold 2.0 > "${tmp}/plain.txt" 2>&1
rc=$?
echo "--- plain rerun (exit ${rc}):"
cat "${tmp}/plain.txt"
check "plain rerun exits 0" test "${rc}" -eq 0
check "plain rerun passes" grep -q "^perf_check: passed" "${tmp}/plain.txt"
check "plain rerun: no benchmark slower" bash -c "! grep -q 'SLOWER' '${tmp}/plain.txt'"
check "plain rerun: launches unchanged" bash -c "! grep -q 'LAUNCHES CHANGED' '${tmp}/plain.txt'"

MINIPAGOSA_PERF_INJECT=single_material MINIPAGOSA_PERF_INJECT_REPEATS=50 \
  "${exe}" --quick --baseline "${tmp}/baseline.json" --threshold 2.0 > "${tmp}/inject.txt" 2>&1
rc=$?
echo "--- injected slowdown (exit ${rc}):"
cat "${tmp}/inject.txt"
check "injected run exits 1" test "${rc}" -eq 1
check "injected run names single_material slower" \
  grep -qE "^\| single_material \|.*\| SLOWER: REGRESSION \|" "${tmp}/inject.txt"
check "injected run: only single_material slower" \
  test "$(grep -c 'SLOWER: REGRESSION' "${tmp}/inject.txt")" -eq 1
# The injection repeats one kernel (lagrange::viscosity, which also resets q's ghosts in the
# same launch) 50 more times per cycle: the launch table must show exactly 50 more, whatever
# the cycle's own count is. (A plain single-material cycle runs the viscosity in the EOS's
# launch, lagrange::eos_viscosity, so its own count of lagrange::viscosity is 0.)
check "injected run: its 50 extra launches named" bash -c \
  "line=\$(grep -E '^\\| single_material \\| [0-9]+ \\| [0-9]+ \\| LAUNCHES CHANGED: .*lagrange::viscosity 0 -> 50' '${tmp}/inject.txt') &&
   base=\$(echo \"\$line\" | awk -F'|' '{print \$3+0}') &&
   now=\$(echo \"\$line\" | awk -F'|' '{print \$4+0}') &&
   test \$((now - base)) -eq 50"
check "injected run says FAILED" grep -q "^perf_check: FAILED" "${tmp}/inject.txt"
exit "${fail}"
