#!/usr/bin/env bash
# Packs a CUDA build of minipagosa for the device machine (issue #51): the executables, every
# test and benchmark, the CTest list of the suite, a host (OpenMP) minipagosa for the CPU side of
# the restart and equality checks, the Debian shared libraries they load, and Open MPI's
# run-time (components, help files, mpirun/orted), in one xz archive under the output folder
# (default .gpu, git-ignored), which the device tool carries (`carry: [".gpu"]`) and
# perf/gpu/run.sh unpacks there. Python wheels for the field comparison (h5py, PyYAML) are
# added when pip can fetch them (the device image has numpy but not these).
#   perf/gpu/pack.sh [--cuda build-cuda] [--cpu build] [--out .gpu]
# (MINIPAGOSA_GPU_XZ=-1: a fast, larger archive for a dry run of the packing here)
# The device image (Ubuntu 24.04, CUDA 13) supplies libc and the driver's libcuda; everything
# else comes from here. Nothing fetched or built from fetched source is committed: the archive
# is an ignored build product.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cuda="${here}/build-cuda"
cpu="${here}/build"
out="${here}/.gpu"
while [ $# -gt 0 ]; do
  case "$1" in
    --cuda) cuda="$(realpath "$2")"; shift 2 ;;
    --cpu) cpu="$(realpath "$2")"; shift 2 ;;
    --out) out="$(realpath -m "$2")"; shift 2 ;;
    *) echo "pack.sh: unknown argument '$1' (--cuda DIR, --cpu DIR, --out DIR)" >&2; exit 2 ;;
  esac
done
log() { echo "[gpu-pack] $*" >&2; }
for d in "${cuda}" "${cpu}"; do
  [ -x "${d}/minipagosa" ] || { log "error: no minipagosa in ${d} (build it first)"; exit 1; }
done
if ! grep -q "KOKKOS_ENABLE_CUDA" "$(sed -n 's/^Kokkos_DIR:PATH=\(.*\)\/lib.*/\1/p' "${cuda}/CMakeCache.txt")/include/KokkosCore_config.h" 2>/dev/null; then
  log "warning: ${cuda} is not built against a CUDA Kokkos (packing it anyway: a dry run)"
fi

stage="$(mktemp -d)"
trap 'rm -rf "${stage}"' EXIT
root="${stage}/mp"
mkdir -p "${root}/build/tests" "${root}/build/perf" "${root}/cpu" "${root}/lib" "${root}/ompi"

# The CUDA build's programs, in the build tree's own layout (tests find ../minipagosa).
cp -p "${cuda}/minipagosa" "${root}/build/"
for sub in tests perf; do
  find "${cuda}/${sub}" -maxdepth 1 -type f -executable -exec cp -p {} "${root}/build/${sub}/" \;
  find "${cuda}/${sub}" -maxdepth 1 -type f -name "*.so" -exec cp -p {} "${root}/build/${sub}/" \;
done
cp -p "${cpu}/minipagosa" "${root}/cpu/"
# The suite as CTest knows it (commands with this machine's paths; run.sh rewrites them).
(cd "${cuda}" && ctest --show-only=json-v1) > "${root}/build/ctest.json"
echo "${cuda}" > "${root}/build/configured_build_dir"
# the CPU build's test costs (run.sh runs the cheapest first)
cp -p "${cpu}/Testing/Temporary/CTestCostData.txt" "${root}/build/" 2>/dev/null || true
git -C "${here}" rev-parse HEAD > "${root}/commit" 2>/dev/null || echo unknown > "${root}/commit"
git -C "${here}" status --short --untracked-files=no | head -20 > "${root}/dirty" || true

# Open MPI's run-time, relocated under ompi/ (OPAL_PREFIX replaces the configured /usr).
ompi_lib=/usr/lib/x86_64-linux-gnu/openmpi
mkdir -p "${root}/ompi/lib/x86_64-linux-gnu" "${root}/ompi/share" "${root}/ompi/bin"
cp -a "${ompi_lib}" "${root}/ompi/lib/x86_64-linux-gnu/"
cp -a /usr/share/openmpi "${root}/ompi/share/"
for b in orterun orted; do cp -pL "/usr/bin/${b}" "${root}/ompi/bin/"; done
ln -s orterun "${root}/ompi/bin/mpirun"
ln -s orterun "${root}/ompi/bin/mpiexec"

# The shared libraries every packed program and MPI component loads, but the C library's own
# and the driver's (the device's are newer and must be used).
skip='^(linux-vdso|ld-linux|libc\.so|libm\.so|libdl\.so|libpthread\.so|librt\.so|libresolv\.so|libutil\.so|libcuda\.so|libnvidia)'
{
  find "${root}/build" "${root}/cpu" "${root}/ompi" -type f \( -executable -o -name "*.so*" \)
} | while read -r f; do ldd "$f" 2>/dev/null || true; done |
  awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | sort -u |
  while read -r name path; do
    if [[ "${name}" =~ ${skip} ]]; then continue; fi
    [ -e "${root}/lib/${name}" ] || cp -pL "${path}" "${root}/lib/${name}"
  done
log "libraries: $(ls "${root}/lib" | wc -l) ($(du -sh "${root}/lib" | cut -f1))"

mkdir -p "${out}"
log "compressing $(du -sh "${root}" | cut -f1) (xz -9 with a 1 GiB window in one thread, which holds every program at once: they share most of their bytes; about 10 GiB of memory and minutes)"
tar -C "${stage}" -cf - mp | xz ${MINIPAGOSA_GPU_XZ:---lzma2=preset=9,dict=1GiB} -T1 > "${out}/minipagosa-gpu.tar.xz"
log "wrote ${out}/minipagosa-gpu.tar.xz ($(du -h "${out}/minipagosa-gpu.tar.xz" | cut -f1))"

# Wheels for the field comparison on the device (Python 3.12 there).
mkdir -p "${out}/wheels"
if python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 \
     --implementation cp --platform manylinux_2_28_x86_64 --platform manylinux_2_17_x86_64 \
     --platform manylinux2014_x86_64 -d "${out}/wheels" h5py PyYAML 2>/dev/null; then
  log "wheels: $(ls "${out}/wheels" | tr '\n' ' ')"
else
  log "warning: no wheels fetched (pip or the index unreachable): run.sh skips the field comparisons"
fi
total=$(du -sm "${out}" | cut -f1)
log "the folder ${out}: ${total} MiB (the device tool carries at most 64 MiB with the working tree)"
if [ "${total}" -gt 56 ]; then log "error: too large to carry"; exit 1; fi
