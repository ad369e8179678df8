#!/usr/bin/env bash
# README command 2: set up, build, and run the whole test suite with CTest.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${MINIPAGOSA_BUILD_DIR:-${here}/build}"
start=$(date +%s)
bash "${here}/ci/build.sh"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cd "${build}"
# Tests declare how many ranks they use (PROCESSORS); ctest packs them onto the cores.
ctest --output-on-failure -j "$(nproc)" --timeout 900
echo "[test] suite finished in $(( $(date +%s) - start )) s (setup + build + tests)"
