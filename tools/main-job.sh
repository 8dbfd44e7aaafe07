#!/bin/bash
# tools/main-job.sh - the main job of the README: installs what is missing, builds the dam-break
# solver, and runs it with the in-situ pipeline (examples/dambreak/main-job.yaml: two views,
# VDB snapshots, stats) on the default renderer (an NVIDIA GPU if present, else llvmpipe), then
# makes a video of the frames with ffmpeg. Outputs go to main-job-output/ (replaced each run):
#   frames/<view>_<step>.png  snapshots/fluid_<step>.vdb  stats.jsonl  stats.png  main-job.mp4
#   log.txt
# Extra arguments go to the solver (e.g. --particles 50000 --until 1.5 for a quicker look).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS

tools/scripts/setup.sh --media
# What the job runs, and the Python module (build/python: the README's `import voxspan`); the
# tests and benchmarks build with tools/scripts/build.sh.
echo "main job: building the solver, the library and its Python module (Release)"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVOXSPAN_WERROR=ON >/dev/null
if ! cmake --build build -j"$(nproc)" --target dambreak insitu-info voxspan_python >build/main-job-build.log 2>&1; then
  grep -E -B2 -A8 "error" build/main-job-build.log | head -60
  echo "main job: the build failed (build/main-job-build.log)"; exit 1
fi
build_seconds=$((SECONDS - start))

echo "main job: renderer"
build/tools/insitu-info | grep -E "^(renders with|platform|renderer|OpenGL) "

out=main-job-output
rm -rf "$out"
mkdir -p "$out"
echo "main job: dam break, about 100 000 particles, until the surge has hit the far wall (T = 2.6)"
run_start=$SECONDS
build/examples/dambreak/dambreak --config examples/dambreak/main-job.yaml \
    --particles 100000 --tank-length 3 --until 2.6 --progress-every 250 "$@" 2>&1 | tee "$out/log.txt"
run_seconds=$((SECONDS - run_start))

# The video: the views side by side (they share a height in the shipped config), 20 frames/s.
views=()
for f in "$out"/frames/*_00000001.png; do
  [[ -e $f ]] && views+=("$(basename "$f" _00000001.png)")
done
video="$out/main-job.mp4"
if ((${#views[@]} > 0)); then
  inputs=()
  for v in "${views[@]}"; do inputs+=(-framerate 20 -pattern_type glob -i "$out/frames/${v}_*.png"); done
  filter="null"
  ((${#views[@]} > 1)) && filter="hstack=inputs=${#views[@]}"
  if ! ffmpeg -loglevel error -y "${inputs[@]}" -filter_complex "$filter" \
      -c:v libx264 -pix_fmt yuv420p -crf 20 "$video" 2>"$out/ffmpeg.txt"; then
    echo "main job: ffmpeg could not make $video (see $out/ffmpeg.txt)"
    video=""
  fi
fi

# The chart of the per-step stats: in-situ time per pass, particles and spans (the system's
# python3, which the apt package python3-matplotlib serves).
chart="$out/stats.png"
if ! /usr/bin/python3 tools/plots/plot_stats.py "$out/stats.jsonl" "$chart" >/dev/null 2>"$out/chart.txt"; then
  echo "main job: no chart (see $out/chart.txt)"
  chart=""
fi

frames=$(find "$out/frames" -name '*.png' | wc -l)
snapshots=$(find "$out/snapshots" -name '*.vdb' 2>/dev/null | wc -l)
echo
echo "main job: summary"
echo "  frames       $frames PNG (${views[*]:-no views}) in $out/frames"
echo "  snapshots    $snapshots VDB in $out/snapshots (inspect: build/tools/inspect_snapshot FILE.vdb)"
grep -E "^time: " "$out/log.txt" | sed 's/^time: /  time         /'
echo "  stats        $(wc -l <"$out/stats.jsonl") lines in $out/stats.jsonl"
[[ -n $chart ]] && echo "  chart        $chart (in-situ time per pass and step)"
[[ -n $video ]] && echo "  video        $video"
echo "  wall time    run ${run_seconds} s, build ${build_seconds} s, whole job $((SECONDS - start)) s"
