#!/bin/bash
# tools/scripts/results.sh [OUT] - the runs and charts of docs/results.md: bench_peers on the solver's
# dam break (about 100 000 particles) calm (T = 0) and collapsing (T = 2), and on its splash
# (T = 5, about 20 000 particles, the solver's run being long), every configuration; then the
# defaults only on the Ritter-profile scene from 10^4 to 10^6 particles (640x360) and from
# 320x180 to 1920x1080 pixels (10^5 particles). CSVs and charts go to OUT (docs/images/results),
# solver states to build/. Takes about half an hour on two cores, most of it the peers (the
# scaling runs time one frame after the warm-up).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=${1:-docs/images/results}
mkdir -p "$out"
bench=build/tools/bench_peers
[[ -x $bench ]] || { echo "results: build first (tools/scripts/build.sh)" >&2; exit 1; }
py=/usr/bin/python3

run() {  # name, then bench_peers' flags
  local name=$1
  shift
  echo "results: $name"
  "$bench" "$@" --csv "$out/$name.csv" | tee "$out/$name.txt"
}
run dambreak_100k_T0 --particles 1e5 --time 0 --state build/dambreak_100k_T0.bin --size 640x360 --frames 5
run dambreak_100k_T2 --particles 1e5 --time 2 --state build/dambreak_100k_T2.bin --size 640x360 --frames 5
run dambreak_20k_T5 --particles 2e4 --time 5 --state build/dambreak_20k_T5.bin --size 640x360 --frames 5
$py tools/plots/plot_peers.py "$out/dambreak" "$out/dambreak_100k_T0.csv" "$out/dambreak_100k_T2.csv" \
  "$out/dambreak_20k_T5.csv" | tee "$out/fronts.txt"

scaling=()
for n in 1e4 1e5 1e6; do
  run "ritter_${n}_640x360" --ritter --particles "$n" --size 640x360 --quick --frames 1
  scaling+=("$out/ritter_${n}_640x360.csv")
done
for size in 320x180 1280x720 1920x1080; do
  run "ritter_1e5_$size" --ritter --particles 1e5 --size "$size" --quick --frames 1
  scaling+=("$out/ritter_1e5_$size.csv")
done
$py tools/plots/plot_peers.py --scaling "$out/scaling.png" "${scaling[@]}"
echo "results: charts and CSVs in $out"
