#!/usr/bin/env bash
# The device run of issue #51, one prepared script for one lease on one H100/H200. Run it on the
# device machine from the repository root with the archive perf/gpu/pack.sh made carried in
# .gpu (device tool: command "bash perf/gpu/run.sh", carry [".gpu"], timeout_s 600):
#   bash perf/gpu/run.sh [PHASE ...]     (default: every phase, in this order)
# Phases and their wall-time budgets (seconds; MINIPAGOSA_GPU_BUDGET_<PHASE> overrides):
#   info        60   nvidia-smi, the archive's commit
#   scene       30   the default scene (Sedov 48^3)
#   tests      150   the CTest suite but its long and perf entries, each under its own limit,
#                    cheapest first (the CPU build's CTest costs); what the budget leaves out
#                    is listed as not run
#   bench       60   bench_hydro at 128^3, 192^3, 256^3 (in-process triad beside it)
#   layouts     60   bench_layouts on 160x128x128 (2.6e6 cells), 2/8/16 materials, 5 % / 50 % mixed
#   restart     60   Sedov 32^3 and the perforator at zone 0.3: a checkpoint written on the GPU
#                    continued on the CPU, and the reverse, each compared field by field with
#                    the uninterrupted run on the other device (tools/compare_builds.py compare)
#   perforator 120   the full perforator deck at zone 0.05 to 60 us (its wall time), then zone
#                    0.025 for what the phase has left (how far it got, its cycle cost, memory)
# Everything it reports lands in $OUT (the device tool brings back at most 8 files):
# gpu_run.md (the report), gpu_run.json, tests.log (the failing tests' output), bench_hydro.json,
# layouts.json, perforator.log. Copy them to perf/results/ and commit them after the lease.
set -uo pipefail
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
pack="${MINIPAGOSA_GPU_PACK:-${repo}/.gpu}"
out="${OUT:-${repo}/gpu-run-out}"
work="${MINIPAGOSA_GPU_WORK:-/tmp/minipagosa-gpu}"
mkdir -p "${out}"
report="${out}/gpu_run.md"
phases=("$@")
[ ${#phases[@]} -gt 0 ] || phases=(info scene tests bench layouts restart perforator)
t0=$(date +%s)
say() { echo "$*" | tee -a "${report}"; }
budget() {
  local v="MINIPAGOSA_GPU_BUDGET_${1^^}"
  echo "${!v:-$2}"
}

if [ ! -d "${work}/mp" ]; then
  mkdir -p "${work}"
  tar -C "${work}" -xJf "${pack}/minipagosa-gpu.tar.xz" || { echo "no archive in ${pack}" >&2; exit 1; }
fi
mp="${work}/mp"
export LD_LIBRARY_PATH="${mp}/lib${LD_LIBRARY_PATH:+:${LD_LIBRARY_PATH}}"
export OPAL_PREFIX="${mp}/ompi" PATH="${mp}/ompi/bin:${PATH}"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
export MINIPAGOSA_SOURCE_DIR="${repo}" OMP_NUM_THREADS="${OMP_NUM_THREADS:-8}" OMP_PROC_BIND=false
export PYTHONUNBUFFERED=1
gpu="${mp}/build/minipagosa"
cpu="${mp}/cpu/minipagosa"
if [ -d "${pack}/wheels" ] && ls "${pack}"/wheels/*.whl >/dev/null 2>&1; then
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
    --target /tmp/minipagosa-site "${pack}"/wheels/*.whl >/dev/null 2>&1 &&
    export PYTHONPATH="/tmp/minipagosa-site${PYTHONPATH:+:${PYTHONPATH}}"
fi

echo "# minipagosa on the device machine, $(date -u +%F)" > "${report}"
say ""
say "Archive: commit $(cat "${mp}/commit")$( [ -s "${mp}/dirty" ] && echo ' (with uncommitted changes)'); phases: ${phases[*]}."

phase_info() {
  say ""
  say "## Device"
  say '```'
  nvidia-smi --query-gpu=name,memory.total,driver_version,clocks.max.sm --format=csv 2>&1 | tee -a "${report}"
  say "$(nproc --all) cores; $(uname -r); $(. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME}")"
  say '```'
}

phase_scene() {
  say ""
  say "## Default scene"
  local s=$(date +%s.%N)
  timeout "$(budget scene 30)" "${gpu}" "${repo}/configs/sedov.yaml" --quiet --output /tmp/mp-scene \
    --overwrite > /tmp/mp-scene.log 2>&1
  local rc=$?
  say "configs/sedov.yaml: exit ${rc}, $(python3 -c "print('%.2f' % ($(date +%s.%N) - ${s}))") s wall; $(grep -h -m1 -i 'energy' /tmp/mp-scene.log | head -c 200)"
}

phase_tests() {
  say ""
  say "## GPU tests (CTest's list, long and perf entries left out)"
  python3 - "${mp}" "$(budget tests 150)" "${out}" <<'PY' | tee -a "${report}"
import json, os, subprocess, sys, time
mp, budget, out = sys.argv[1], float(sys.argv[2]), sys.argv[3]
old = open(os.path.join(mp, "build", "configured_build_dir")).read().strip()
new = os.path.join(mp, "build")
src = os.environ["MINIPAGOSA_SOURCE_DIR"]
oldsrc = os.path.dirname(old)
tests = json.load(open(os.path.join(new, "ctest.json")))["tests"]
# cheapest first (the CPU build's CTest costs, where packed), so a short budget runs the most
cost = {}
try:
    for line in open(os.path.join(new, "CTestCostData.txt")):
        f = line.split()
        if len(f) == 3:
            cost[f[0]] = float(f[2])
except OSError:
    pass
tests.sort(key=lambda t: cost.get(t["name"], 1e9))
def prop(t, name, default=None):
    for p in t.get("properties", []):
        if p["name"] == name:
            return p["value"]
    return default
def fix(a):
    a = a.replace(old, new).replace(oldsrc, src)
    if os.path.basename(a) in ("mpiexec", "mpirun"):
        return "mpirun"
    return a
rows, t_start = [], time.time()
log = open(os.path.join(out, "tests.log"), "w")
for t in tests:
    labels = prop(t, "LABELS", [])
    if "long" in labels or "perf" in labels or "long_pin" in labels:
        continue
    left = budget - (time.time() - t_start)
    if left < 5:
        rows.append((t["name"], "not run", 0.0, labels)); continue
    cmd = [fix(a) for a in t["command"]]
    env = dict(os.environ)
    for kv in prop(t, "ENVIRONMENT", []):
        k, v = kv.split("=", 1)
        env[k] = v
    env["OMP_NUM_THREADS"] = "4"
    s = time.time()
    try:
        p = subprocess.run(cmd, cwd=fix(prop(t, "WORKING_DIRECTORY", new)), env=env,
                           capture_output=True, text=True,
                           timeout=min(float(prop(t, "TIMEOUT", 120)), 120, left))
        ok = p.returncode == 0 and "[==========] 0 tests from" not in p.stdout
        status = "passed" if ok else "FAILED"
        if not ok:
            log.write("==== %s (exit %d)\n%s\n%s\n" % (t["name"], p.returncode,
                      p.stdout[-6000:], p.stderr[-3000:]))
    except subprocess.TimeoutExpired:
        status = "timeout"
        log.write("==== %s: timeout\n" % t["name"])
    rows.append((t["name"], status, time.time() - s, labels))
n = {k: sum(1 for r in rows if r[1] == k) for k in ("passed", "FAILED", "timeout", "not run")}
print("%d entries: %d passed, %d failed, %d timed out, %d not run (budget %.0f s, used %.0f s)\n"
      % (len(rows), n["passed"], n["FAILED"], n["timeout"], n["not run"], budget,
         time.time() - t_start))
print("| entry | result | s |\n|---|---|---|")
for r in rows:
    if r[1] != "passed":
        print("| %s | %s | %.1f |" % (r[0], r[1], r[2]))
json.dump([{"name": r[0], "result": r[1], "seconds": r[2], "labels": r[3]} for r in rows],
          open("/tmp/mp-tests.json", "w"), indent=1)
PY
}

phase_bench() {
  say ""
  say "## Single-material cycle (bench_hydro)"
  (cd "${mp}/build/perf" && timeout "$(budget bench 60)" ./bench_hydro --sizes 128,192,256 --cycles 10 \
    --json "${out}/bench_hydro.json" > /tmp/mp-bench.log 2>&1)
  say "exit $?; the JSON: bench_hydro.json"
  say '```'
  grep -E "^\s*(cells|[0-9]+\^3|triad|STREAM)|Mcell|% of" /tmp/mp-bench.log | head -30 | tee -a "${report}"
  say '```'
}

phase_layouts() {
  say ""
  say "## Layouts (bench_layouts, 160x128x128)"
  (cd "${mp}/build/perf" && timeout "$(budget layouts 60)" ./bench_layouts --cells 160,128,128 \
    --materials 2,8,16 --widths 20,2 --cycles 5 --repeats 3 --no-breakdown \
    --json "${out}/layouts.json" --note "device run, perf/gpu/run.sh" > /tmp/mp-layouts.log 2>&1)
  say "exit $?; the JSON: layouts.json"
  say '```'
  grep -iE "dense|compact|ratio" /tmp/mp-layouts.log | head -30 | tee -a "${report}"
  say '```'
}

# run EXE DECK OUTDIR [--set ...]: a quiet run writing dumps (first and last) and checkpoints
run_case() {
  local exe="$1" deck="$2" dir="$3"; shift 3
  rm -rf "${dir}"
  "${exe}" "${repo}/configs/${deck}" --quiet --output "${dir}" --set output.write=true \
    --set output.interval=0 "$@" > "${dir}.log" 2>&1
}

phase_restart() {
  say ""
  say "## Restart across devices (checkpoint on one, continued on the other)"
  local limit=$(( $(date +%s) + $(budget restart 60) ))
  python3 - <<'PY' > /dev/null 2>&1 || { say "no h5py/yaml on this machine (wheels not carried): skipped"; return; }
import h5py, yaml, numpy
PY
  for c in "sedov.yaml|mesh.cells=[32,32,32]|time.max_cycles=60|30" \
           "perforator.yaml|mesh.zone=0.3|time.max_cycles=40|20"; do
    IFS='|' read -r deck a b half <<< "${c}"
    [ "$(date +%s)" -lt "${limit}" ] || { say "${deck}: not run (budget)"; continue; }
    local base=/tmp/mp-rs-${deck%.yaml}
    run_case "${gpu}" "${deck}" "${base}-gpu" --set "${a}" --set "${b}"
    run_case "${cpu}" "${deck}" "${base}-cpu" --set "${a}" --set "${b}"
    run_case "${gpu}" "${deck}" "${base}-g2c" --set "${a}" --set "${b}" \
      --set "output.checkpoint_every.cycles=${half}"
    run_case "${cpu}" "${deck}" "${base}-c2g" --set "${a}" --set "${b}" \
      --set "output.checkpoint_every.cycles=${half}"
    # continue each from its middle checkpoint on the other device, into a folder of its own
    local ck_g ck_c tag
    tag=$(printf %06d "${half}")
    ck_g=$(ls "${base}-g2c"/*_checkpoint_"${tag}".h5 2>/dev/null | head -1)
    ck_c=$(ls "${base}-c2g"/*_checkpoint_"${tag}".h5 2>/dev/null | head -1)
    [ -n "${ck_g}" ] && run_case "${cpu}" "${deck}" "${base}-g2c-cont" --set "${a}" --set "${b}" \
      --restart "${ck_g}"
    [ -n "${ck_c}" ] && run_case "${gpu}" "${deck}" "${base}-c2g-cont" --set "${a}" --set "${b}" \
      --restart "${ck_c}"
    python3 - "${repo}" "${base}" "${deck}" <<'PY' | tee -a "${report}"
import os, sys, tempfile
sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
from compare_builds import compare
base, deck = sys.argv[2], sys.argv[3]
def last(d):
    return [f for f in sorted(os.listdir(d)) if f.endswith(".h5") and "checkpoint" not in f][-1]
pairs = (("gpu", "cpu", "GPU run = CPU run"),
         ("g2c-cont", "cpu", "GPU checkpoint continued on the CPU = CPU run"),
         ("c2g-cont", "gpu", "CPU checkpoint continued on the GPU = GPU run"))
for a, b, what in pairs:
    try:
        la, lb = last(base + "-" + a), last(base + "-" + b)
        if la != lb:
            raise RuntimeError("last dumps %s vs %s" % (la, lb))
        ta, tb = tempfile.mkdtemp(), tempfile.mkdtemp()
        os.symlink(os.path.join(base + "-" + a, la), os.path.join(ta, la))
        os.symlink(os.path.join(base + "-" + b, lb), os.path.join(tb, lb))
        n, bad, why = compare(ta, tb)
        print("- %s, %s (%s): %d values compared, %d differ %s" % (deck, what, la, n, bad,
              "; ".join(why[:3])))
    except Exception as e:
        print("- %s, %s: no comparison (%s)" % (deck, what, e))
PY
  done
  say "(exact equality is the claim only for a build with MINIPAGOSA_NO_FMA=ON; with FMAs the counts say how far contraction moves the fields)"
}

phase_perforator() {
  say ""
  say "## The perforator, full deck"
  local limit=$(( $(date +%s) + $(budget perforator 120) ))
  : > "${out}/perforator.log"
  for zone in 0.05 0.025; do
    local left=$(( limit - $(date +%s) ))
    [ "${left}" -gt 10 ] || { say "- zone ${zone}: not run (budget)"; continue; }
    local dir=/tmp/mp-perf-${zone}
    rm -rf "${dir}"
    say "- zone ${zone}: $("${gpu}" "${repo}/configs/perforator.yaml" --check --set "mesh.zone=${zone}" 2>&1 | grep -m1 "memory estimate" | sed 's/^ *//' | cut -c1-160)"
    local s=$(date +%s.%N)
    timeout "${left}" "${gpu}" "${repo}/configs/perforator.yaml" --output "${dir}" \
      --set "mesh.zone=${zone}" --set output.write=true --set output.interval=10 \
      > "${dir}.log" 2>&1
    local rc=$? w
    w=$(python3 -c "print('%.1f' % ($(date +%s.%N) - ${s}))")
    tail -n 25 "${dir}.log" >> "${out}/perforator.log"
    local last
    last=$(grep -E "^ *(cycle|[0-9]+ )" "${dir}.log" | tail -n 1 | head -c 200)
    say "- zone ${zone}: exit ${rc} ($([ ${rc} = 124 ] && echo "stopped by the budget" || echo finished)), ${w} s wall; last log line: ${last}"
    [ -f "${dir}/summary.json" ] && python3 -c "
import json; s = json.load(open('${dir}/summary.json'))
print('  cells %s, cycles %s, t %s us, wall %s s, %.3g cell-cycles/s' % (s.get('cells'), s.get('cycles'), s.get('time'), s.get('wall_seconds'), s.get('cell_cycles_per_second') or 0))" | tee -a "${report}"
    [ -f "${dir}/summary.json" ] && cp "${dir}/summary.json" "${out}/perforator_${zone}_summary.json" 2>/dev/null
  done
}

for p in "${phases[@]}"; do
  case "${p}" in
    info | scene | tests | bench | layouts | restart | perforator) "phase_${p}" ;;
    *) say "unknown phase '${p}'" ;;
  esac
done
[ -f /tmp/mp-tests.json ] && cp /tmp/mp-tests.json "${out}/gpu_run.json"
say ""
say "Total $(( $(date +%s) - t0 )) s."
