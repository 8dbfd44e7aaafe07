#!/bin/sh
# snapshot_check.sh MPIEXEC RANKS RENDER_PARTICLES COMPARE CONFIG PARTICLES OUT: one process and
# RANKS ranks write the snapshots of CONFIG, in unequal slabs with the last rank empty;
# compare_snapshots holds the second to the first.
set -eu
mpiexec=$1 ranks=$2 render=$3 compare=$4 config=$5 particles=$6 out=$7
rm -rf "$out"
"$render" --config "$config" --output "$out/one" "$particles"
"$mpiexec" --oversubscribe -n "$ranks" "$render" --split uneven --config "$config" --output "$out/many" "$particles"
"$compare" "$out/one" "$out/many"
