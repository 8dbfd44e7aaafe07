#!/bin/bash
# tools/scripts/setup.sh [--media] - installs, with apt, the Debian 12 packages the build, the tests and
# (with --media) the main job need, and only those missing. Does nothing when all are present.
set -euo pipefail

packages=(
  g++ make cmake pkg-config lld                      # toolchain (CMake 3.25 on Debian 12; lld links)
  libegl-dev libgl-dev libepoxy-dev                  # EGL + GL through libglvnd, epoxy loader
  libegl-mesa0 libgl1-mesa-dri                       # Mesa: llvmpipe when there is no GPU
  libglm-dev libtbb-dev libyaml-cpp-dev libpng-dev   # math, threads, config, images
  libdeflate-dev                                     # the PNG frames' compression
  libopenvdb-dev libboost-iostreams-dev              # snapshots (OpenVDB's CMake needs boost-iostreams)
  libvtk9-dev                                        # .vtp/.vtu/.vti/.pvd files
  libopenexr-dev                                     # depth (and deep) images
  libhdf5-dev                                        # PySPH's HDF5 particle files (offline tools)
  libmuparser-dev                                    # the expressions of the triggers' conditions
  libcivetweb-dev                                    # the live page's HTTP server
  chromium                                           # the live page's test in a real browser
  libopenmpi-dev openmpi-bin                         # many ranks
  libembree-dev                                      # Embree against the CPU caster (tools/bench_embree)
  libgtest-dev gfortran clang-format                 # tests (gfortran: the Fortran bindings)
  pybind11-dev python3-dev python3-numpy            # the Python module voxspan
  python3-pytest python3-mpi4py                      # its tests (pytest; two ranks through mpi4py)
  python3-pysph python3-h5py                         # PySPH's 3D dam break, a solver not ours
                                                     # (test_default_view_pysph); it brings g++
                                                     # and python3-dev for the Cython it compiles;
                                                     # without h5py it writes .npz, not .hdf5
)
if [[ ${1:-} == --media ]]; then
  packages+=(ffmpeg python3-matplotlib)              # the main job's video and charts
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present, nothing to install"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=()
if ((EUID != 0)); then
  command -v sudo >/dev/null || { echo "setup: error: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: installed ${#missing[@]} packages"
