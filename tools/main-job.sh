#!/bin/bash
# tools/main-job.sh - the main job of the README: installs what is missing, builds, and runs
# the in-situ pipeline on the default renderer (NVIDIA if present, else llvmpipe).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh --media
tools/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
build/tools/insitu-info
