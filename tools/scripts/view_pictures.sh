#!/bin/bash
# tools/scripts/view_pictures.sh - the pictures of the particles, slice and coloured surface
# views in docs/images/ and the README: the WCSPH dam break (examples/dambreak) with about 50 000 particles run to T = 1.8,
# when the surge runs along the floor, with examples/dambreak/views.yaml (the particles coloured
# by speed, the pressure on the tank's vertical mid-plane, that slice placed among the particles,
# the surface coloured by speed); the last step's frames are kept as
# docs/images/dambreak_particles_speed.png, dambreak_slice_pressure.png,
# dambreak_particles_slice.png and dambreak_surface_speed.png.
# Needs the Release build (tools/scripts/build.sh). Extra arguments go to the solver.
set -euo pipefail
cd "$(dirname "$0")/../.."
cmake --build build --target dambreak >/dev/null
rm -rf views-output
build/examples/dambreak/dambreak --config examples/dambreak/views.yaml \
    --particles 50000 --tank-length 3 --until 1.8 --progress-every 500 "$@"
last() { ls views-output/frames/"$1"_*.png | sort | tail -1; }
cp "$(last speed)" docs/images/dambreak_particles_speed.png
cp "$(last pressure)" docs/images/dambreak_slice_pressure.png
cp "$(last inside)" docs/images/dambreak_particles_slice.png
cp "$(last surface_speed)" docs/images/dambreak_surface_speed.png
echo "view_pictures: wrote docs/images/dambreak_{particles_speed,slice_pressure,particles_slice,surface_speed}.png"
