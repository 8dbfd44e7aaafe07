#!/bin/sh
# fortran_bindings_check.sh SOURCE_DIR: every function the C API declares
# (sim_adapter/voxspan/voxspan.h) has its bind(C) interface in the Fortran module
# (sim_adapter/fortran/voxspan.f90), under its own name or a name="..." that gives it: a Fortran
# solver can make every call a C solver can. Names the missing ones.
set -eu
cd "$1"
status=0
for f in $(grep -oE '\bvoxspan_[a-z0-9_]+\(' sim_adapter/voxspan/voxspan.h | tr -d '(' | sort -u); do
  if ! grep -qiE "(function|subroutine) +$f *\(|name=\"$f\"" sim_adapter/fortran/voxspan.f90; then
    echo "sim_adapter/fortran/voxspan.f90: no binding of $f"
    status=1
  fi
done
[ $status -eq 0 ] && echo "bindings OK"
exit $status
