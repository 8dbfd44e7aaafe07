#!/bin/bash
# tools/scripts/dambreak_mpi_check.sh [PARTICLES [RANKS...]] [-- DAMBREAK_OPTIONS...] - the dam break
# under mpiexec against the serial run: runs examples/dambreak (Release build, tools/scripts/build.sh)
# without rendering to T = 1 and to T = 2 on 1 rank (the serial solver) and on each of RANKS
# (default 2 4, oversubscribed where the machine has fewer cores), and prints per run the
# front x/a, its difference from the serial run's, whether every step kept every fluid particle
# on exactly one rank, and the median solver step. Fails when a front differs by more than 2 %
# or a run lost a particle. Default: 30 000 particles.
set -euo pipefail
cd "$(dirname "$0")/../.."
particles=${1:-30000}
shift $(($# > 0 ? 1 : 0))
ranks=()
while (($# > 0)) && [[ $1 != -- ]]; do ranks+=("$1"); shift; done
(($# > 0)) && shift
((${#ranks[@]} > 0)) || ranks=(2 4)
exe=build/examples/dambreak/dambreak
[[ -x $exe ]] || { echo "dambreak_mpi_check: build first (tools/scripts/build.sh)" >&2; exit 1; }
# Open MPI refuses to start as root without these.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

failed=0
printf "%-5s %-3s %-10s %-10s %-24s %s\n" ranks T "front x/a" "vs serial" "particles" \
  "median step"
for until in 1 2; do
  serial=
  for n in 1 "${ranks[@]}"; do
    out=$(mpiexec --oversubscribe -n "$n" "$exe" --particles "$particles" --until "$until" \
      --no-render --progress-every 0 "$@")
    front=$(sed -n 's/^final: .*front x\/a \([0-9.]*\).*/\1/p' <<<"$out")
    step=$(sed -n 's/.*(median step \([0-9.]*\) ms).*/\1/p' <<<"$out")
    count=$(sed -n 's/^final: .*fluid particles \([0-9]*\).*/\1/p' <<<"$out")
    if ((n == 1)); then
      serial=$front conserved="$count (serial)"
    elif grep -q "fluid particles on every step, ids each owned once" <<<"$out"; then
      conserved="$count on every step"
    else
      conserved="NOT CONSERVED" failed=1
    fi
    diff=$(awk -v a="$front" -v b="$serial" 'BEGIN { printf "%+.3f %%", 100 * (a - b) / b }')
    awk -v a="$front" -v b="$serial" 'BEGIN { exit !(a - b > 0.02 * b || b - a > 0.02 * b) }' &&
      failed=1
    printf "%-5s %-3s %-10s %-10s %-24s %s ms\n" "$n" "$until" "$front" "$diff" "$conserved" "$step"
  done
done
exit $failed
