#!/usr/bin/env bash
# CTest test kernel_profile_smoke (label perf): the kernel-profile library (kernel_profile.cpp)
# loaded into a run of configs/sod_x.yaml writes its JSON, and its counts are the run's: one
# lagrange::acceleration and one timestep::cfl launch per cycle (summary.json's cycles), kernel
# time within the wall time.
#   kernel_profile_test.sh MINIPAGOSA_EXE PROFILE_LIBRARY DECK
set -euo pipefail
exe="$1" lib="$2" deck="$3"
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
OMP_NUM_THREADS=1 OMP_PROC_BIND=false KOKKOS_PROFILE_LIBRARY="${lib}" \
  MINIPAGOSA_KERNEL_PROFILE="${tmp}/profile.json" "${exe}" "${deck}" -q -o "${tmp}/out" > /dev/null
python3 - "${tmp}/profile.json" "${tmp}/out/summary.json" <<'PY'
import json, sys
p = json.load(open(sys.argv[1]))
cycles = json.load(open(sys.argv[2]))["cycles"]
k = {x["name"]: x for x in p["kernels"]}
bad = []
for name in ("lagrange::acceleration", "timestep::cfl"):
    got = k.get(name, {}).get("launches")
    if got != cycles:
        bad.append(f"{name}: {got} launches, {cycles} cycles")
if not 0 < p["kernel_seconds"] <= p["wall_seconds"]:
    bad.append(f"kernel seconds {p['kernel_seconds']} against wall {p['wall_seconds']}")
if p["launches"] != sum(x["launches"] for x in p["kernels"]):
    bad.append("launch total differs from the sum over kernels")
print(f"kernel_profile: {len(k)} kernels, {p['launches']} launches, {cycles} cycles,"
      f" {p['kernel_seconds']:.3f} of {p['wall_seconds']:.3f} s")
for b in bad:
    print("FAILED:", b)
sys.exit(1 if bad else 0)
PY
