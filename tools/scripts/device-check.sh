#!/bin/bash
# tools/scripts/device-check.sh BUNDLE[.tar.gz] OUT [--debs DIR] [--quick] [--budget S]
# The table of docs/benchmarks.md's "NVIDIA H200" section, refreshed in one call on a GPU machine
# (one NVIDIA H200, 16 cores: meant to take under 4 minutes, unpacking included; not yet timed
# there, the budget below keeps it within), from a bundle made by tools/scripts/make-bundle.sh
# (the GPU machine needs no compiler or package manager; BUNDLE may also be a build folder,
# whose tools/ is used). The steps, most wanted first, each into OUT/<step>.txt; each prints
# its seconds, the last line the total:
#   insitu-info          the renderer, GL version and limits (NVIDIA EGL works);
#   shading_8.5m         bench_shading --ritter --all-particles --particles 7e6 (8.5 M, all
#                        voxelized) at 1920x1080x16384, alpha 1, 1 GiB tiles: every mode;
#   shading_122m         bench_shading --ritter --particles 100e6 (122 M, boundary shell), 1080p,
#                        translucent;
#   renderers_1e6        bench_renderers --ritter --particles 1e6 --time 0.25 at 1920x1080: the GL
#                        renderer on the GPU against the CPU renderer on the cores, opaque and
#                        refractive;
#   renderers_1e7        the same with 1e7 particles (11.5 M), opaque;
#   insitu_1080p         bench_insitu --particles 1e6 --start 0.05 --steps 100 --render-every 10
#                        --vdb-every 50 --non-render-steps 1000000, the main job's two views at
#                        1920x1080 (its runs: the solver alone, rendering, rendering + VDB);
#   insitu_640x360       the same at the main job's 640x360, 50 steps;
#   insitu_1080p_wait    insitu_1080p with `renderer: {readback: wait}`: the pictures read back
#                        at once, as before reading later (the default on a GPU) existed;
#   insitu_1080p_linear  insitu_1080p with --linear-pictures: floats read back and encoded on the
#                        writer's thread, as before the GPU made the PNG pictures 8-bit sRGB;
#   shading_16.3m        as shading_8.5m with --particles 13.35e6 --budget-mib 2048, translucent
#                        and refractive;
#   shading_8.5m_4k      as shading_8.5m at 3840x2160, translucent and refractive;
#   shading_61m          bench_shading --ritter --particles 50e6 (61 M, boundary shell), 1080p,
#                        translucent;
#   voxelize_8.5m        bench_voxelize --particles 7e6 --all-particles at 1920x1080x16384, 1 GiB
#                        tiles (lists, --no-resplat), per pixel and per particle;
#   renderers_1e5        bench_renderers --ritter --particles 1e5 at 640x360, opaque, refractive;
#   pictures/            render_pictures of the Ritter dam break at 960x540, to compare with the
#                        llvmpipe pictures made here:
#                          build/tools/render_pictures --ritter --out /tmp/llvmpipe --compare OUT/pictures
#   spans.bin            the span image of bench_voxelize's default scene, to compare with
#                        llvmpipe's:
#                          build/tools/bench_voxelize --frames 1 --no-resplat --budget-mib 1024 \
#                            --threads per_particle --compare-spans OUT/spans.bin
#   volume_*             bench_volume --gl (the volume views' GL march on the GPU: its time, its
#                        difference from the CPU frame): Ritter 1e5 at 640x360, 1e6 at 1920x1080
#                        and 1024x1024 (DVR, iso).
#   classify_1t, _all    bench_classify --particles 5e6 (the dam break's 5 M) on one thread and
#                        on all: the adapter's classification without the solver's grid, and how
#                        it scales with the cores.
# The benches time 3 frames after a warm-up (--quick: 1); most of a step's time is building its
# scene on the CPU. Each step runs under `timeout`, within its own limit and the time left of the
# budget (--budget S, default 230 s from the start, --quick 900; a step with under 5 s left is
# skipped: when time runs short, the last steps are the ones left out); a failing step is
# reported and the others still run. At the end: one markdown table (row,
# measured, goal; also OUT/summary.md) of the figures the section's table quotes, parsed from
# the steps' outputs, with the issue's goals and whether they are met, and the count of GL
# performance warnings in every step's output.
# --debs DIR: unpack these .deb files (the GL vendor-neutral dispatch, libglvnd, for a machine
#             whose driver comes without it) into / first.
# --quick:    the same steps at small sizes, to check the script and its summary (here, on
#             llvmpipe: tools/scripts/device-check.sh build /tmp/device-check --quick).
set -uo pipefail
if (($# < 2)); then
  awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"  # the header above
  exit 2
fi
repo=$(realpath "$(dirname "$0")/../..")
bundle=$(realpath "$1")
out=$(realpath -m "$2")
if [[ $bundle == *.tar.gz ]]; then
  unpacked=$(mktemp -d)
  trap 'rm -rf "$unpacked"' EXIT
  tar -C "$unpacked" -xzf "$bundle"
  bundle=$(echo "$unpacked"/*)
fi
shift 2
quick=0
budget=
while (($#)); do
  case $1 in
    --debs) for f in "$2"/*.deb; do dpkg -x "$f" /; done; ldconfig; shift 2 ;;
    --quick) quick=1; shift ;;
    --budget) budget=$2; shift 2 ;;
    *) echo "device-check: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -n $budget ]] || budget=$((quick ? 900 : 230))
bin=$bundle/bin
[[ -d $bin ]] || bin=$bundle/tools  # a build folder
mkdir -p "$out"
failed=0
declare -A state took
steps=()

# step LIMIT NAME COMMAND...: runs COMMAND with its output in OUT/NAME.txt, timed, under
# `timeout` (LIMIT seconds, or the time left of the budget when less).
step() {
  local limit=$1 name=$2
  shift 2
  steps+=("$name")
  local left=$((budget - SECONDS))
  if ((left < 5)); then
    echo "device-check: $name skipped: ${left} s left of the ${budget} s budget"
    state[$name]="skipped, out of time"
    took[$name]=0
    failed=1
    return
  fi
  ((limit > left)) && limit=$left
  local start=$SECONDS rc=0
  echo "device-check: $name (limit $limit s): $*"
  timeout -k 5 "$limit" "$@" >"$out/$name.txt" 2>&1 || rc=$?
  took[$name]=$((SECONDS - start))
  if ((rc == 0)); then
    state[$name]=ok
    echo "device-check: $name done in ${took[$name]} s"
    return
  fi
  if ((rc == 124 || rc == 137)); then
    state[$name]="timed out (limit $limit s)"
  else
    state[$name]="failed (exit $rc)"
  fi
  echo "device-check: $name ${state[$name]} after ${took[$name]} s; last lines:"
  tail -5 "$out/$name.txt"
  failed=1
}

# The sizes: the section's, or --quick's small ones (same steps, same parsing).
if ((quick)); then
  frames=1 hd=320x180 uhd=640x360 low=160x90 square=128x128
  all_1=2e4 all_2=4e4 shell_1=1e5 shell_2=2e5 ren_1=2e4 ren_2=1e5 ren_low=5e3
  pic=(--particles 2e4 --size 320x180) spans=(--particles 2e4 --size 320x180)
  insitu=(--particles 5000 --non-render-steps 1000) insitu_steps=20 insitu_low_steps=20
  vol_low=2e4 vol_1=2e4 cls=2e5
else
  frames=3 hd=1920x1080 uhd=3840x2160 low=640x360 square=1024x1024
  all_1=7e6 all_2=13.35e6 shell_1=50e6 shell_2=100e6 ren_1=1e6 ren_2=1e7 ren_low=1e5
  pic=() spans=()
  insitu=(--particles 1e6 --non-render-steps 1000000) insitu_steps=100 insitu_low_steps=50
  vol_low=1e5 vol_1=1e6 cls=5e6
fi
all=(--ritter --all-particles --alpha 1 --max-layers 16384 --frames "$frames")
insitu+=(--config "$repo/examples/dambreak/main-job.yaml" --start 0.05 --render-every 10
  --vdb-every 50)

step 30 insitu-info "$bin/insitu-info"
step 45 shading_8.5m "$bin/bench_shading" "${all[@]}" --particles "$all_1" --size "$hd" \
  --budget-mib 1024
step 75 shading_122m "$bin/bench_shading" --ritter --particles "$shell_2" --size "$hd" \
  --frames "$frames" --modes translucent
step 40 renderers_1e6 "$bin/bench_renderers" --ritter --particles "$ren_1" --time 0.25 \
  --size "$hd" --frames "$frames" --modes opaque,refractive
step 45 renderers_1e7 "$bin/bench_renderers" --ritter --particles "$ren_2" --time 0.25 \
  --size "$hd" --frames "$frames" --modes opaque
if [[ -x $bin/bench_insitu ]]; then
  step 60 insitu_1080p "$bin/bench_insitu" "${insitu[@]}" --steps "$insitu_steps" --size "$hd"
  step 50 insitu_640x360 "$bin/bench_insitu" "${insitu[@]}" --steps "$insitu_low_steps" \
    --size "$low"
  # The last --config wins: the main job's, reading its pictures at once.
  wait_config="$out/main-job-readback-wait.yaml"
  { cat "$repo/examples/dambreak/main-job.yaml"; echo "renderer: {readback: wait}"; } >"$wait_config"
  step 60 insitu_1080p_wait "$bin/bench_insitu" "${insitu[@]}" --config "$wait_config" \
    --steps "$insitu_steps" --size "$hd"
  step 60 insitu_1080p_linear "$bin/bench_insitu" "${insitu[@]}" --steps "$insitu_steps" \
    --size "$hd" --linear-pictures
else
  echo "device-check: insitu steps skipped: the bundle has no bench_insitu"
fi
step 45 shading_16.3m "$bin/bench_shading" "${all[@]}" --particles "$all_2" --size "$hd" \
  --budget-mib 2048 --modes translucent,refractive
step 45 shading_8.5m_4k "$bin/bench_shading" "${all[@]}" --particles "$all_1" --size "$uhd" \
  --budget-mib 1024 --modes translucent,refractive
step 50 shading_61m "$bin/bench_shading" --ritter --particles "$shell_1" --size "$hd" \
  --frames "$frames" --modes translucent
step 40 voxelize_8.5m "$bin/bench_voxelize" --all-particles --particles "$all_1" --size "$hd" \
  --alpha 1 --max-layers 16384 --budget-mib 1024 --no-resplat --frames "$frames"
step 20 renderers_1e5 "$bin/bench_renderers" --ritter --particles "$ren_low" --size "$low" \
  --frames "$frames" --modes opaque,refractive
step 30 pictures "$bin/render_pictures" --ritter "${pic[@]}" --out "$out/pictures"
step 30 spans "$bin/bench_voxelize" "${spans[@]}" --frames 1 --no-resplat --budget-mib 1024 \
  --threads per_particle --save-spans "$out/spans.bin"
step 30 volume_1e5 "$bin/bench_volume" --ritter --particles "$vol_low" --size "$low" \
  --frames "$frames" --gl
step 30 volume_1e6_1080p "$bin/bench_volume" --ritter --particles "$vol_1" --size "$hd" \
  --frames "$frames" --modes dvr,iso --gl
step 30 volume_1e6_1024 "$bin/bench_volume" --ritter --particles "$vol_1" --size "$square" \
  --frames "$frames" --modes dvr,iso --gl
step 30 classify_1t "$bin/bench_classify" --particles "$cls" --steps 1 --repeats 7 --threads 1
step 20 classify_all "$bin/bench_classify" --particles "$cls" --steps 1 --repeats 7

# The summary: parsers of the tools' outputs (an empty answer when the figure is missing).
outfile() { echo "$out/$1.txt"; }
# count STEP WORD: the number before WORD (or "WORD,") on the step's scene line, as "8.5 M".
count() {
  awk -v w="$2" '/^(scene|dam break):/ {
      for (i = 1; i < NF; i++) {
        n = $(i + 1); sub(/,$/, "", n)
        if (n == w && $i ~ /^[0-9]+$/) {
          if ($i >= 1e6) printf "%.1f M\n", $i / 1e6
          else if ($i >= 1e3) printf "%.0f k\n", $i / 1e3
          else print $i
          exit
        }
      }
      exit
    }' "$(outfile "$1")" 2>/dev/null
}
# shading STEP MODE: bench_shading's total ms of MODE.
shading() { awk -v m="$2" '$1 == m && $2 ~ /^[0-9.]+$/ { print $(NF - 1); exit }' "$(outfile "$1")" 2>/dev/null; }
# renderers STEP MODE gl|cpu: bench_renderers' step ms (classify + frame + read-back).
renderers() { awk -v m="$2" -v r="$3" '$1 == m && $2 == r { print $NF; exit }' "$(outfile "$1")" 2>/dev/null; }
# voxelize STEP "per pixel"|"per particle": bench_voxelize's total ms, first budget, tile lists.
voxelize() { awk -v t="lists, $2 " 'index($0, t) { print $(NF - 3); exit }' "$(outfile "$1")" 2>/dev/null; }
# share STEP RUN: bench_insitu's extra wall over the solver alone, %, of RUN ("render, no
# snapshots" or "render + VDB snapshots").
share() { awk -v r="$2" 'index($0, r) == 1 { print $(NF - 1); exit }' "$(outfile "$1")" 2>/dev/null; }
# solver_ms STEP: the solver alone, ms per step.
solver_ms() {
  awk '/^solver alone/ { sub(/.*\(/, ""); sub(/ ms per step.*/, ""); print; exit }' \
    "$(outfile "$1")" 2>/dev/null
}
# thread_ms STEP: the solver thread's ms per render step in the run without snapshots, the sum
# of its passes and of "classify+compact+outputs".
thread_ms() {
  awk 'index($0, "render, no snapshots") == 1 { run = 1; next }
       run && /per render step, ms:/ {
         for (i = 1; i <= NF; i++) { t = $i; sub(/;$/, "", t); if (t ~ /^[0-9]+(\.[0-9]+)?$/) s += t }
         printf "%.1f\n", s; exit
       }' "$(outfile "$1")" 2>/dev/null
}
# nogrid STEP: bench_classify's particles a second without the solver's grid.
nogrid() { awk '$1 ~ /^[0-9]+$/ && NF >= 10 { print $8; exit }' "$(outfile "$1")" 2>/dev/null; }
# figures STEP UNIT VALUE...: "a / b / c UNIT", "?" for a missing value, and why the step gave
# none when it did not end well.
figures() {
  local name=$1 unit=$2 text="" v
  shift 2
  for v in "$@"; do text+="${text:+ / }${v:-?}"; done
  [[ $text =~ [0-9] ]] && text+="${unit:+ $unit}"
  [[ $text == *"?"* && ${state[$name]:-not run} != ok ]] && text+=" (${name}: ${state[$name]:-not run})"
  echo "$text"
}
# goal VALUE LIMIT UNIT: "≤ LIMIT UNIT: met" (or missed, or no figure).
goal() {
  local verdict="no figure"
  if [[ $1 =~ ^[-+]?[0-9]+(\.[0-9]+)?$ ]]; then
    verdict=$(awk -v v="$1" -v l="$2" 'BEGIN { print (v <= l ? "met" : "missed") }')
  fi
  echo "≤ $2${3:+ $3}: $verdict"
}
# with VALUE UNIT: "VALUE UNIT", or nothing when VALUE is.
with() { [[ -n $1 ]] && echo "$1 $2"; }

summary() {
  local n b st sr go gr sh ms
  echo "GL renderer: $(awk '$1 == "renderer" { $1 = ""; print substr($0, 2); exit }' \
    "$(outfile insitu-info)" 2>/dev/null); the runtime renders with: $(awk '/^renders with/ {
      sub(/^renders with +/, ""); print; exit }' "$(outfile insitu-info)" 2>/dev/null)"
  echo
  echo "| row | measured | goal |"
  echo "|---|---|---|"
  r() { echo "| $1 | $2 | ${3:-} |"; }  # a row: label, measured, goal

  n=$(count shading_8.5m voxelized)
  st=$(shading shading_8.5m translucent) sr=$(shading shading_8.5m refractive)
  r "bench_shading, ${n:-?} all voxelized, $hd: opaque / translucent / refractive" \
    "$(figures shading_8.5m ms "$(shading shading_8.5m opaque)" "$st" "$sr")" \
    "translucent $(goal "$st" 12 ms); refractive $(goal "$sr" 25 ms)"
  n=$(count shading_16.3m voxelized)
  r "same, ${n:-?}: translucent / refractive" \
    "$(figures shading_16.3m ms "$(shading shading_16.3m translucent)" \
      "$(shading shading_16.3m refractive)")"
  n=$(count shading_8.5m_4k voxelized)
  r "same, ${n:-?} at $uhd: translucent / refractive" \
    "$(figures shading_8.5m_4k ms "$(shading shading_8.5m_4k translucent)" \
      "$(shading shading_8.5m_4k refractive)")"
  n=$(count shading_61m particles) b=$(count shading_61m voxelized)
  r "bench_shading, ${n:-?} (${b:-?} boundary shell), $hd: translucent" \
    "$(figures shading_61m ms "$(shading shading_61m translucent)")"
  n=$(count shading_122m particles) b=$(count shading_122m voxelized)
  st=$(shading shading_122m translucent)
  r "bench_shading, ${n:-?} (${b:-?} boundary shell), $hd: translucent" \
    "$(figures shading_122m ms "$st")" "$(goal "$st" 20 ms)"
  n=$(count voxelize_8.5m voxelized)
  r "bench_voxelize, ${n:-?} all voxelized, $hd: per pixel / per particle" \
    "$(figures voxelize_8.5m ms "$(voxelize voxelize_8.5m "per pixel")" \
      "$(voxelize voxelize_8.5m "per particle")")"
  n=$(count renderers_1e6 particles)
  go=$(renderers renderers_1e6 opaque gl) gr=$(renderers renderers_1e6 refractive gl)
  r "bench_renderers, ${n:-?}, $hd, step: GL opaque / refractive, CPU opaque / refractive" \
    "$(figures renderers_1e6 ms "$go" "$gr" "$(renderers renderers_1e6 opaque cpu)" \
      "$(renderers renderers_1e6 refractive cpu)")" "GL opaque $(goal "$go" 12 ms)"
  n=$(count renderers_1e7 particles) b=$(count renderers_1e7 boundary)
  go=$(renderers renderers_1e7 opaque gl)
  r "bench_renderers, ${n:-?} (${b:-?} boundary), $hd, step: GL opaque, CPU opaque" \
    "$(figures renderers_1e7 ms "$go" "$(renderers renderers_1e7 opaque cpu)")" \
    "GL opaque $(goal "$go" 30 ms)"
  n=$(count renderers_1e5 particles)
  r "bench_renderers, ${n:-?}, $low, step: GL opaque / refractive, CPU opaque / refractive" \
    "$(figures renderers_1e5 ms "$(renderers renderers_1e5 opaque gl)" \
      "$(renderers renderers_1e5 refractive gl)" "$(renderers renderers_1e5 opaque cpu)" \
      "$(renderers renderers_1e5 refractive cpu)")"
  n=$(count insitu_640x360 fluid)
  r "bench_insitu, ${n:-?}, the main job's two views at ${low} every 10 steps: in-situ share over the solver / solver alone per step" \
    "$(figures insitu_640x360 "" "$(with "$(share insitu_640x360 "render, no snapshots")" %)" \
      "$(with "$(solver_ms insitu_640x360)" ms)")"
  n=$(count insitu_1080p fluid)
  sh=$(share insitu_1080p "render, no snapshots") ms=$(thread_ms insitu_1080p)
  r "bench_insitu, ${n:-?}, the two views at ${hd}: in-situ share / with a VDB every 50 steps / solver thread per render step" \
    "$(figures insitu_1080p "" "$(with "$sh" %)" \
      "$(with "$(share insitu_1080p "render + VDB snapshots")" %)" "$(with "$ms" ms)")" \
    "share $(goal "$sh" 3 %); per render step $(goal "$ms" 15 ms)"
  r "the same, solver thread per render step: pictures read later (\`readback: auto\`) / at once (\`wait\`) / as floats (\`--linear-pictures\`)" \
    "$(figures insitu_1080p_wait "" "$(with "$ms" ms)" "$(with "$(thread_ms insitu_1080p_wait)" ms)" \
      "$(with "$(thread_ms insitu_1080p_linear)" ms)")"
  local c1 ca
  c1=$(nogrid classify_1t) ca=$(nogrid classify_all)
  r "bench_classify, the dam break's $cls particles without the solver's grid: particles/s on 1 thread / on all (speed-up)" \
    "$(figures "$([[ -z $c1 ]] && echo classify_1t || echo classify_all)" "" "$c1" "$ca")$(awk -v a="$c1" -v b="$ca" 'BEGIN {
      if (a > 0 && b > 0) printf " (x%.1f)", b / a }')" "scales with the cores"
  local w=0 where="" s c
  for s in "${steps[@]}"; do
    c=$(grep -ci "performance warning" "$(outfile "$s")" 2>/dev/null) || true
    ((${c:-0} > 0)) && w=$((w + c)) where+="${where:+, }$s $c"
  done
  r "GL performance warnings in the steps' output (default log level)" "$w${where:+ ($where)}" \
    "0: $( ((w == 0)) && echo met || echo missed)"
}

echo
summary | tee "$out/summary.md"
echo
line="device-check: steps, s:"
for s in "${steps[@]}"; do
  line+=" $s ${took[$s]}"
  [[ ${state[$s]} == ok ]] || line+=" (${state[$s]})"
  line+=","
done
echo "${line%,}"
echo "device-check: outputs in $out; total $SECONDS s (budget $budget s)"
exit "$failed"
