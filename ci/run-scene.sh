#!/usr/bin/env bash
# README command 1: set up, build, and run a scene end to end (default: the 3-D Sedov blast),
# writing HDF5 dumps, the XDMF series and summary.json into output/<scene>/ (replacing an earlier
# run's files there).
#   bash ci/run-scene.sh [configs/SCENE.yaml] [-- extra minipagosa options]
# MINIPAGOSA_RANKS (default 2) MPI ranks, MINIPAGOSA_THREADS (default 1) OpenMP threads each.
# It builds the executable alone (MINIPAGOSA_BUILD_TARGETS="" builds every target).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MINIPAGOSA_BUILD_DIR:-${here}/build}"
scene="${1:-${here}/configs/sedov.yaml}"
shift || true
[ "${1:-}" = "--" ] && shift
MINIPAGOSA_BUILD_TARGETS="${MINIPAGOSA_BUILD_TARGETS-minipagosa}" bash "${here}/ci/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMP_NUM_THREADS="${MINIPAGOSA_THREADS:-1}" OMP_PROC_BIND=false
cd "${here}"
# A second run of the same scene replaces the first one's files (the program itself refuses to
# mix runs in one directory unless told to); --restart continues in place instead.
extra=(--overwrite)
for a in "$@"; do
  case "$a" in --overwrite | --restart | --restart=*) extra=() ;; esac
done
# Open MPI binds each rank of a one- or two-rank job to one core: with more than one thread a
# rank, its threads would share that core, so they are left unbound then.
bind=()
[ "${OMP_NUM_THREADS}" != 1 ] && bind=(--bind-to none)
mpiexec -np "${MINIPAGOSA_RANKS:-2}" --oversubscribe "${bind[@]}" "${build}/minipagosa" "${scene}" \
  "${extra[@]}" "$@"
