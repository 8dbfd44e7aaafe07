#!/bin/sh
# check.sh BUILD_DIR WORK_DIR: installs the build into WORK_DIR/prefix, then configures, builds
# and runs tests/package as an outside project would (CMake: C++, C, MPI, Fortran), and builds
# the C consumer with pkg-config alone, as a Makefile would.
set -eu
build=$1; work=$2; here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$here" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_cpp"
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_c"
if [ -x "$work/consumer/consumer_f" ]; then
  LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_f"
fi
# Nothing but standard-library headers reached the solver's compile lines (MPI's aside).
if grep -rqE "vtk|openvdb|epoxy|EGL" "$work/consumer/CMakeFiles"/*/flags.make; then
  echo "FAIL: private dependencies leaked into the solver's compile flags"; exit 1
fi
pc=$(find "$work/prefix" -name voxspan.pc)
# shellcheck disable=SC2046
cc "$here/consumer.c" -o "$work/consumer_c_pc" \
  $(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags --libs voxspan)
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer_c_pc"
echo "package OK"
