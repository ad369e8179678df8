#!/usr/bin/env bash
# Compiles every target of minipagosa (library, executable, tests, perf harness) with nvcc
# against a CUDA Kokkos, in a build directory of its own; nothing is run, so no GPU is needed.
# It catches what only nvcc rejects (an extended lambda in a private member function, in a
# generic lambda, or taking a function-local type; see README "GPU builds").
#   MINIPAGOSA_CUDA_KOKKOS     the CUDA Kokkos install prefix
#                              (default: ~/.cache/minipagosa/kokkos-4.7.01-cuda)
#   MINIPAGOSA_CUDA_BUILD_DIR  the build directory (default: ./build-cuda)
#   MINIPAGOSA_JOBS            parallel compiles (default: nproc)
# Extra arguments go to CMake (e.g. -DMINIPAGOSA_NO_FMA=ON). With no CUDA Kokkos at that prefix
# it prints "skipped: no CUDA Kokkos at <prefix>" and exits 0; a Kokkos there without CUDA, or
# no nvcc, is an error.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cache="${MINIPAGOSA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/minipagosa}"
kokkos="${MINIPAGOSA_CUDA_KOKKOS:-${cache}/kokkos-4.7.01-cuda}"
build="$(realpath -m "${MINIPAGOSA_CUDA_BUILD_DIR:-${here}/build-cuda}")"
jobs="${MINIPAGOSA_JOBS:-$(nproc)}"

config=""
for dir in lib lib64; do
  if [ -f "${kokkos}/${dir}/cmake/Kokkos/KokkosConfig.cmake" ]; then
    config="${kokkos}/${dir}/cmake/Kokkos"
  fi
done
if [ -z "${config}" ]; then
  echo "[cuda-check] skipped: no CUDA Kokkos at ${kokkos}"
  exit 0
fi
if ! grep -q '^#define KOKKOS_ENABLE_CUDA' "${kokkos}/include/KokkosCore_config.h" 2>/dev/null; then
  echo "[cuda-check] error: the Kokkos at ${kokkos} has no CUDA backend" >&2
  exit 1
fi
wrapper="${kokkos}/bin/nvcc_wrapper"
if [ ! -x "${wrapper}" ]; then
  echo "[cuda-check] error: no nvcc_wrapper in ${kokkos}/bin" >&2
  exit 1
fi
if ! command -v nvcc >/dev/null 2>&1 && [ -x /usr/local/cuda/bin/nvcc ]; then
  export PATH="/usr/local/cuda/bin:${PATH}"
fi
if ! command -v nvcc >/dev/null 2>&1; then
  echo "[cuda-check] error: no nvcc on PATH (nor in /usr/local/cuda/bin)" >&2
  exit 1
fi
version=$(sed -n 's/^set(PACKAGE_VERSION "\(.*\)")$/\1/p' "${config}/KokkosConfigVersion.cmake" | head -n 1)
echo "[cuda-check] Kokkos ${version} (CUDA) at ${kokkos}; $(nvcc --version | grep -o "release [0-9.]*" | head -n 1)"

start=$(date +%s)
# a build directory configured against another Kokkos (its cache names another compiler) is
# configured afresh: CMake refuses to change the compiler of an existing cache
if [ -f "${build}/CMakeCache.txt" ] &&
  ! grep -qx "CMAKE_CXX_COMPILER:[A-Z]*=${wrapper}" "${build}/CMakeCache.txt"; then
  echo "[cuda-check] ${build} was configured with another compiler: configuring it afresh"
  rm -rf "${build}/CMakeCache.txt" "${build}/CMakeFiles"
fi
if [ ! -f "${build}/CMakeCache.txt" ] || [ $# -gt 0 ]; then
  cmake -S "${here}" -B "${build}" -DCMAKE_BUILD_TYPE=Release -DKokkos_ROOT="${kokkos}" \
    -DCMAKE_CXX_COMPILER="${wrapper}" "$@"
fi
# keep going past a failed file (Makefiles): one run lists every file nvcc rejects
keep=()
if [ -f "${build}/Makefile" ]; then keep=(-- -k); fi
status=0
cmake --build "${build}" -j "${jobs}" "${keep[@]}" || status=$?
if [ "${status}" != 0 ]; then
  echo "[cuda-check] FAILED: nvcc rejected some files (above) in ${build}" >&2
  exit "${status}"
fi
echo "[cuda-check] every target compiled with nvcc in ${build} in $(( $(date +%s) - start )) s"
