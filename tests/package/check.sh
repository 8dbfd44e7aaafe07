#!/bin/sh
# check.sh BUILD_DIR WORK_DIR: installs the build into WORK_DIR/prefix, then configures, builds
# and runs tests/package as an outside project would.
set -eu
build=$1; work=$2; here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$here" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_cpp"
LD_LIBRARY_PATH="$work/prefix/lib" "$work/consumer/consumer_c"
# Nothing but standard-library headers reached the solver's compile lines.
if grep -rqE "vtk|openvdb|epoxy|EGL" "$work/consumer/CMakeFiles"/*/flags.make; then
  echo "FAIL: private dependencies leaked into the solver's compile flags"; exit 1
fi
echo "package OK"
