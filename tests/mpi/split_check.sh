#!/bin/sh
# split_check.sh MPIEXEC RANKS SPLIT RENDER_PARTICLES COMPARE CONFIG PARTICLES REFERENCE OUT:
# the offline renderer on RANKS ranks with --split SPLIT writes the pictures and depth images
# of one process (REFERENCE): compare_outputs holds them to it.
set -eu
mpiexec=$1 ranks=$2 split=$3 render=$4 compare=$5 config=$6 particles=$7 reference=$8 out=$9
rm -rf "$out"
"$mpiexec" --oversubscribe -n "$ranks" "$render" --split "$split" --config "$config" \
  --output "$out" "$particles"
"$compare" "$reference" "$out"
