#!/usr/bin/env bash
# The checks kept out of README command 2's fast path, in the double build that ci/test.sh left
# in ./build (or $MINIPAGOSA_BUILD_DIR): the label long (Noh at 64^3 and 96^3, the third-order
# remap's convergence and comparisons, products into air at 1600 cells) and the kind pin (the
# regression pins and known misses: they guard against a change, they prove no claim), and the
# smoke tests of perf/'s tools (tradeoff, the kernel profile library), whose two programs it
# builds first. .ci/run runs it after ci/test.sh.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(realpath -m "${MINIPAGOSA_BUILD_DIR:-${here}/build}")"
if [ ! -f "${build}/CTestTestfile.cmake" ]; then
  echo "ci/long.sh: no test build in ${build}; run bash ci/test.sh first" >&2
  exit 1
fi
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
start=$(date +%s)
targets=(tests_all)
grep -q '^MINIPAGOSA_ENABLE_PERF:BOOL=OFF' "${build}/CMakeCache.txt" || targets+=(perf_tools)
blog="${build}/long-build.log"
if ! cmake --build "${build}" -j "$(nproc)" --target "${targets[@]}" > "${blog}" 2>&1; then
  cat "${blog}" >&2
  echo "ci/long.sh: the build failed (log: ${blog})" >&2
  exit 1
fi
cd "${build}"
ctest --output-on-failure -j "$(nproc)" --timeout 900 -L 'long|pin' -LE perf
echo "[long] long checks and pins finished in $(( $(date +%s) - start )) s"
