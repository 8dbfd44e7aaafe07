#!/bin/bash
# tools/scripts/device-check.sh BUNDLE[.tar.gz] OUT [--debs DIR] [--quick]
# Everything docs/benchmarks.md wants from a GPU machine, in one run (not yet timed on a GPU; each
# step prints its seconds, and the 7 M-particle scenes are built on the CPU three times), from a
# bundle made by tools/scripts/make-bundle.sh (the GPU machine needs no compiler or package manager):
#   insitu-info        the renderer, GL version and limits (issue: NVIDIA EGL works);
#   pictures/          render_pictures of the Ritter dam break at 960x540, to compare with the
#                      llvmpipe pictures made here:
#                        build/tools/render_pictures --ritter --out /tmp/llvmpipe --compare OUT/pictures
#   voxelize_*.txt     bench_voxelize: the llvmpipe rows' settings, then 1920x1080x16384 with
#                      about 7 M voxelized particles (two tile budgets);
#   spans.bin          the span image of the llvmpipe rows' scene, to compare with llvmpipe's:
#                        build/tools/bench_voxelize --frames 1 --no-resplat --budget-mib 1024 \
#                          --threads per_particle --compare-spans OUT/spans.bin
#   shading_*.txt      bench_shading: the same two scales, every mode, with and without deep AO;
#   renderers_*.txt    bench_renderers: the GL renderer on the GPU against the CPU renderer on
#                      the machine's cores, per pass, and the PSNR of their pictures;
#   peers_*.txt        bench_peers: both renderers over their settings (GL on the GPU) against
#                      OpenVDB's and VTK's paths and the exact caster (docs/results.md);
#   insitu.txt         bench_insitu: the in-situ cost against the WCSPH solver at the main job's
#                      settings, one render every 10 steps (when the bundle carries it);
#   views_*.txt        bench_views: the particles and slice views (CPU code with either
#                      renderer) on the machine's cores, Table 1 and 10^5-10^6 particles;
#   volume_*.txt       bench_volume: the volume views' CPU renderer on the machine's cores and
#                      the GL march on the GPU (--gl: its time, its difference from the CPU
#                      frame), the dam-break goals' sizes and Fraedrich's;
#   composite.txt      bench_composite on 2 ranks sharing the GPU at 1920x1080, when the machine
#                      has Open MPI's mpiexec (the bundle carries libmpi, not the launcher).
# Each step writes OUT/<step>.txt; a failing step is reported and the others still run.
# --debs DIR: unpack these .deb files (the GL vendor-neutral dispatch, libglvnd, for a machine
#             whose driver comes without it) into / first.
# --quick:    small sizes only, to check the script itself (here, on llvmpipe).
set -uo pipefail
if (($# < 2)); then
  awk 'NR > 1 && !/^#/ { exit } NR > 1 { sub(/^# ?/, ""); print }' "$0"  # the header above
  exit 2
fi
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
while (($#)); do
  case $1 in
    --debs) for f in "$2"/*.deb; do dpkg -x "$f" /; done; ldconfig; shift 2 ;;
    --quick) quick=1; shift ;;
    *) echo "device-check: unknown argument $1" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
failed=0

# step NAME COMMAND...: runs COMMAND with its output in OUT/NAME.txt, timed.
step() {
  local name=$1
  shift
  local start=$SECONDS
  echo "device-check: $name: $*"
  if "$@" >"$out/$name.txt" 2>&1; then
    echo "device-check: $name done in $((SECONDS - start)) s"
  else
    echo "device-check: $name FAILED (exit $?) after $((SECONDS - start)) s; last lines:"
    tail -5 "$out/$name.txt"
    failed=1
  fi
}

bin=$bundle/bin
step insitu-info "$bin/insitu-info"
if ((quick)); then
  step pictures "$bin/render_pictures" --ritter --particles 2e4 --size 320x180 --out "$out/pictures"
  step voxelize_small "$bin/bench_voxelize" --particles 2e4 --size 320x180 --frames 2 --json \
    --save-spans "$out/spans.bin"
  step shading_small "$bin/bench_shading" --ritter --particles 2e4 --size 320x180 --frames 2
  step renderers_small "$bin/bench_renderers" --ritter --particles 2e4 --size 320x180 --frames 2
  step peers_small "$bin/bench_peers" --ritter --particles 2e4 --size 320x180 --frames 1 --quick \
    --check
  [[ -x $bin/bench_insitu ]] &&
    step insitu "$bin/bench_insitu" --particles 5000 --start 0.1 --steps 20 --render-every 10 \
      --vdb-every 20
  step views_small "$bin/bench_views" --table-particles 2e4 --counts 2e4 --frames 1
  step volume_small "$bin/bench_volume" --ritter --particles 2e4 --size 320x180 --frames 1
else
  step pictures "$bin/render_pictures" --ritter --out "$out/pictures"
  step voxelize_llvmpipe_rows "$bin/bench_voxelize" --frames 5 --budget-mib 1024 --budget-mib 16 \
    --budget-mib 4 --json --save-spans "$out/spans.bin"
  step shading_llvmpipe_rows "$bin/bench_shading" --ritter --particles 1e6 --time 0.25 --frames 3
  # The GPU against the CPU renderer on this machine's cores: times and the pictures' PSNR.
  step renderers_1080p "$bin/bench_renderers" --ritter --particles 1e6 --time 0.25 \
    --size 1920x1080 --frames 3
  step peers_640x360 "$bin/bench_peers" --ritter --particles 1e5 --size 640x360 --frames 3
  step voxelize_7m "$bin/bench_voxelize" --particles 7e6 --all-particles --size 1920x1080 \
    --alpha 1 --max-layers 16384 --budget-mib 1024 --budget-mib 256 --frames 10 --json
  step shading_7m "$bin/bench_shading" --ritter --all-particles --particles 7e6 --size 1920x1080 \
    --alpha 1 --max-layers 16384 --budget-mib 1024 --frames 10 --json
  step shading_7m_ao "$bin/bench_shading" --ritter --all-particles --particles 7e6 \
    --size 1920x1080 --alpha 1 --max-layers 16384 --budget-mib 1024 --frames 10 --ao \
    --modes translucent
  [[ -x $bin/bench_insitu ]] &&
    step insitu "$bin/bench_insitu" --steps 300 --render-every 10 --vdb-every 100
  step views_1e6 "$bin/bench_views" --table-particles 1e6 --counts 1e5,1e6 --frames 3
  step volume_1e5 "$bin/bench_volume" --ritter --particles 1e5 --size 640x360 --frames 5 --gl
  step volume_1e6_1080p "$bin/bench_volume" --ritter --particles 1e6 --size 1920x1080 --frames 3 \
    --modes dvr,iso --gl
  step volume_1e6_1024 "$bin/bench_volume" --ritter --particles 1e6 --size 1024x1024 --frames 3 \
    --modes dvr,iso --gl
fi

# composite_step ARGS...: bench_composite on 2 ranks, where this machine can start them (Open
# MPI 4 calls its launcher OpenRTE, 5 PRRTE; the bundle's libmpi needs Open MPI's).
composite_step() {
  if mpiexec --version 2>/dev/null | grep -q -e OpenRTE -e PRRTE -e "Open MPI"; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # root on the machine
    step composite mpiexec --oversubscribe -n 2 "$bin/bench_composite" "$@"
  else
    echo "device-check: composite skipped: no Open MPI mpiexec on this machine"
  fi
}
if ((quick)); then
  composite_step --particles 2e4 --size 160x90 --frames 1
else
  composite_step --particles 1e6 --size 1920x1080 --frames 3
fi
echo "device-check: outputs in $out"
exit "$failed"
