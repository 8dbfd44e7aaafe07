#!/bin/bash
# tools/scripts/pysph_dambreak.sh [--dx DX] [--tf T] [--pfreq N] [--compress] OUTDIR - runs PySPH's own
# 3D dam break (pysph.examples.dam_break_3d from Debian's python3-pysph: SPHERIC test 2, a
# column 1.228 x 1 x 0.55 m in a 3.22 m tank with an obstacle, WCSPH, arrays fluid, boundary
# and obstacle) into OUTDIR, then prints its .hdf5 files, one a line, in time order: a solver
# no one here wrote, whose files the offline renderer must read as they are.
#   --dx DX     particle spacing in metres (default 0.05: 5016 fluid and 9988 wall and obstacle
#               particles)
#   --tf T      simulated time in seconds (default 0.3: the column has collapsed and its surge
#               runs along the floor)
#   --pfreq N   steps between output files (default 200); PySPH also writes step 0, the last
#               step and t = 0.4, 0.6, 1.0 (the example's own output times)
#   --compress  gzip the HDF5 datasets (PySPH's -z)
# PYTHON names the interpreter (default /usr/bin/python3: a python3 found first on PATH, from
# pyenv or a venv, does not see Debian's packages). Exit status 77 when PySPH is not installed
# (tools/scripts/setup.sh installs it), PySPH's own otherwise.
# At its first run PySPH generates and compiles Cython code for the equations (g++ and
# python3-dev; cached in ~/.pysph/source, about 20 s); the run itself is one thread. At the
# defaults it takes about 1 minute on one core (docs/runtime.md, "The first picture at any
# scale").
set -euo pipefail

usage() {
  echo "usage: tools/scripts/pysph_dambreak.sh [--dx DX] [--tf T] [--pfreq N] [--compress] OUTDIR" >&2
  exit "${1:-2}"
}
dx=0.05 tf=0.3 pfreq=200 compress=() out=
while (($#)); do
  case $1 in
    --dx) (($# > 1)) || usage; dx=$2; shift 2 ;;
    --tf) (($# > 1)) || usage; tf=$2; shift 2 ;;
    --pfreq) (($# > 1)) || usage; pfreq=$2; shift 2 ;;
    --compress) compress=(-z); shift ;;
    -h | --help) usage 0 ;;
    -*) echo "pysph_dambreak: unknown option $1" >&2; usage ;;
    *) [[ -z $out ]] || usage; out=$1; shift ;;
  esac
done
[[ -n $out ]] || usage
python=${PYTHON:-/usr/bin/python3}
if ! "$python" -c 'import pysph' 2>/dev/null; then
  echo "pysph_dambreak: $python cannot import pysph (python3-pysph; tools/scripts/setup.sh installs it)" >&2
  exit 77
fi
if ! "$python" -c 'import h5py' 2>/dev/null; then
  # Without h5py PySPH writes .npz files instead, silently.
  echo "pysph_dambreak: $python cannot import h5py (python3-h5py; tools/scripts/setup.sh installs it)" >&2
  exit 1
fi

mkdir -p "$out"
rm -f "$out"/dam_break_3d_*.hdf5  # a previous run's files would pass for this one's
# The application without the example's post-processing (pressure probes against Kleefsman's
# data, plotted with matplotlib): the same run as `python3 -m pysph.examples.dam_break_3d`.
# One thread: beside a parallel build on 2 cores OpenMP's run took 3x as long as one thread's.
args=(--dx "$dx" --tf "$tf" --pfreq "$pfreq" "${compress[@]}" -d "$out" --no-openmp)
echo "pysph_dambreak: $python -m pysph.examples.dam_break_3d ${args[*]} (without its post-processing)"
start=$SECONDS
"$python" -c '
import sys
from pysph.examples.dam_break_3d import DamBreak3D
DamBreak3D(fname="dam_break_3d").run(sys.argv[1:])
' "${args[@]}" >"$out/pysph.log" 2>&1 || {
  status=$?
  tail -n 20 "$out/pysph.log" >&2
  echo "pysph_dambreak: PySPH failed (status $status; $out/pysph.log)" >&2
  exit "$status"
}
grep -E "fluid|boundary|obstacle|took" "$out/pysph.log" | head -n 8 || true
echo "pysph_dambreak: $((SECONDS - start)) s; the files:"
ls "$out"/dam_break_3d_*.hdf5 | sort
