#!/bin/bash
# tools/scripts/volume_pictures.sh - the volume views' pictures in docs/images/ and the README:
# the WCSPH dam break (examples/dambreak) with about 50 000 particles run to T = 1.8, when the
# surge runs along the floor, with examples/dambreak/volume.yaml (the pressure as direct volume
# rendering, the speed's iso surfaces, the speed in mixed mode); the last step's frames are kept
# as docs/images/dambreak_volume_pressure.png, dambreak_volume_speed_iso.png and
# dambreak_volume_mixed.png. Then PySPH's own dam break (tools/scripts/pysph_dambreak.sh) at
# t = 0.3 s through examples/pysph/volume.yaml, kept as docs/images/pysph_volume.png (skipped
# when PySPH is not installed).
# Needs the Release build (tools/scripts/build.sh). Extra arguments go to the solver.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build --target dambreak render_particles >/dev/null
rm -rf volume-output
build/examples/dambreak/dambreak --config examples/dambreak/volume.yaml \
    --particles 50000 --tank-length 3 --until 1.8 --progress-every 500 "$@"
last() { ls volume-output/frames/"$1"_*.png | sort | tail -1; }
cp "$(last pressure_volume)" docs/images/dambreak_volume_pressure.png
cp "$(last speed_iso)" docs/images/dambreak_volume_speed_iso.png
cp "$(last speed_mixed)" docs/images/dambreak_volume_mixed.png
echo "volume_pictures: wrote docs/images/dambreak_volume_{pressure,speed_iso,mixed}.png"

pysph_run=$(mktemp -d)
trap 'rm -rf "$pysph_run"' EXIT
status=0
files=$(tools/scripts/pysph_dambreak.sh --tf 0.3 "$pysph_run") || status=$?
if ((status == 77)); then
  echo "volume_pictures: PySPH is not installed; no docs/images/pysph_volume.png"
  exit 0
fi
((status == 0)) || exit "$status"
last_file=$(tail -1 <<<"$files")
rm -rf pysph-volume-output
build/tools/render_particles --config examples/pysph/volume.yaml --arrays fluid \
    --output pysph-volume-output \
    "$last_file"
cp "$(ls pysph-volume-output/frames/*.png | sort | tail -1)" docs/images/pysph_volume.png
echo "volume_pictures: wrote docs/images/pysph_volume.png"
