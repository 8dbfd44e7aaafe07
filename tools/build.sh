#!/bin/bash
# tools/build.sh - configures and builds the project in build/ (Release, warnings as errors,
# as CI builds it). Extra arguments go to the configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DVOXSPAN_WERROR=ON "$@" >/dev/null
cmake --build build -j"$(nproc)"
