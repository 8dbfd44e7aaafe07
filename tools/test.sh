#!/bin/bash
# tools/test.sh - the test command of the README and of CI: installs what is missing, builds
# with warnings as errors, runs every test (GL tests on llvmpipe when there is no GPU).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh
# Open MPI refuses to run as root without these (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ctest --test-dir build --output-on-failure -j"$(nproc)"
