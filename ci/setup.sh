#!/usr/bin/env bash
# Installs what minipagosa needs on Debian 12 and reuses what is already there.
#   - Debian packages: Open MPI, parallel HDF5, yaml-cpp, CLI11, nlohmann-json, GoogleTest,
#     Google Benchmark, Python numpy/h5py/matplotlib, ccache (only the missing ones are installed).
#   - Kokkos with the OpenMP and Serial backends, built from packages/kokkos of Debian's
#     `trilinos` source package into a cache prefix outside the repository (DESIGN.md §1).
#     Debian's binary Trilinos Kokkos is Serial-only and is never used.
# With Kokkos_ROOT set in the environment, that Kokkos is used instead and nothing is built.
# Prints the Kokkos prefix on its last line as `KOKKOS_ROOT=<path>`.
set -euo pipefail

log() { echo "[setup] $*" >&2; }

SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi

packages=(
  g++ cmake make dpkg-dev xz-utils ccache
  libopenmpi-dev openmpi-bin libhdf5-openmpi-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libgtest-dev libbenchmark-dev
  python3 python3-numpy python3-h5py python3-matplotlib python3-yaml
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

cache="${MINIPAGOSA_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/minipagosa}"
prefix="${cache}/kokkos-trilinos-openmp"
need_kokkos=0
if [ -z "${Kokkos_ROOT:-}" ] && [ ! -f "${prefix}/lib/cmake/Kokkos/KokkosConfig.cmake" ] &&
   [ ! -f "${prefix}/lib64/cmake/Kokkos/KokkosConfig.cmake" ]; then
  need_kokkos=1
fi

# A deb-src entry for the trilinos source package (Kokkos below), derived from the machine's
# own sources; prints whether one was added (an apt-get update must follow).
add_deb_src() {
  if apt-get source --download-only --print-uris trilinos >/dev/null 2>&1; then
    echo 0
    return
  fi
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    sed -e 's/^Types:.*/Types: deb-src/' /etc/apt/sources.list.d/debian.sources \
      | $SUDO tee /etc/apt/sources.list.d/minipagosa-deb-src.sources >/dev/null
  elif [ -f /etc/apt/sources.list ]; then
    grep -E '^deb ' /etc/apt/sources.list | sed -e 's/^deb /deb-src /' \
      | $SUDO tee /etc/apt/sources.list.d/minipagosa-deb-src.list >/dev/null
  else
    log "no apt sources found to derive a deb-src entry from"
    exit 1
  fi
  echo 1
}

# Kokkos with the OpenMP and Serial backends from packages/kokkos of Debian's trilinos source
# package, installed in ${prefix}. Needs g++, cmake, make, tar and gzip only (no other package
# of the list above), so on a bare machine it runs beside the package install.
build_kokkos() {
  log "building Kokkos (OpenMP+Serial) from Debian's trilinos source package into ${prefix}"
  local work="${cache}/kokkos-build"
  rm -rf "${work}"
  mkdir -p "${work}"
  (cd "${work}" && apt-get source --download-only -q trilinos >&2)
  local orig top src
  orig=$(ls "${work}"/trilinos_*.orig.tar.* | head -n 1)
  log "extracting packages/kokkos from $(basename "${orig}")"
  top=$( (tar -tf "${orig}" || true) 2>/dev/null | head -n 1 | cut -d/ -f1)
  tar -xf "${orig}" -C "${work}" "${top}/packages/kokkos"
  src="${work}/${top}/packages/kokkos"
  cmake -S "${src}" -B "${work}/build" \
    -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_COMPILER=g++ \
    -DCMAKE_CXX_STANDARD=17 \
    -DCMAKE_INSTALL_PREFIX="${prefix}" \
    -DCMAKE_POSITION_INDEPENDENT_CODE=ON \
    -DKokkos_ENABLE_SERIAL=ON \
    -DKokkos_ENABLE_OPENMP=ON \
    -DKokkos_ENABLE_TESTS=OFF \
    -DKokkos_ENABLE_EXAMPLES=OFF >&2
  cmake --build "${work}/build" -j "$(nproc)" >&2
  cmake --install "${work}/build" >&2
  rm -rf "${work}"
  log "Kokkos installed in ${prefix}"
}

kpid=""
if [ ${#missing[@]} -gt 0 ]; then
  log "installing Debian packages: ${missing[*]}"
  # one apt-get update for the packages and, where Kokkos is to be built, its source package
  [ "${need_kokkos}" = 1 ] && add_deb_src >/dev/null
  $SUDO apt-get update -q >&2
  # Kokkos beside the install when its tools are here already (a bare Debian 12 machine with a
  # compiler: the install's dpkg work and the Kokkos compile overlap, about 20 s of setup's 60)
  if [ "${need_kokkos}" = 1 ] && command -v g++ >/dev/null && command -v cmake >/dev/null &&
     command -v make >/dev/null; then
    build_kokkos &
    kpid=$!
  fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends \
    "${missing[@]}" >&2
else
  log "Debian packages: all present"
fi

if [ -n "${Kokkos_ROOT:-}" ]; then
  log "using Kokkos_ROOT=${Kokkos_ROOT} from the environment"
  echo "KOKKOS_ROOT=${Kokkos_ROOT}"
  exit 0
fi
if [ -n "${kpid}" ]; then
  if ! wait "${kpid}"; then
    log "the Kokkos build failed"
    exit 1
  fi
elif [ "${need_kokkos}" = 1 ]; then
  if [ "$(add_deb_src)" = 1 ]; then $SUDO apt-get update -q >&2; fi
  build_kokkos
else
  log "Kokkos (OpenMP+Serial) found in ${prefix}"
fi
echo "KOKKOS_ROOT=${prefix}"
