#!/bin/bash
# tools/scripts/build.sh [--sanitize] [CMAKE_ARGS...] - configures and builds the project with
# warnings as errors, as CI builds it: Release in build/, or with --sanitize the sanitizer
# build (AddressSanitizer + UndefinedBehaviorSanitizer, assertions on) in build-sanitize/.
# Extra arguments go to the configure step.
set -euo pipefail
cd "$(dirname "$0")/../.."
dir=build
config=(-DCMAKE_BUILD_TYPE=Release)
if [[ ${1:-} == --sanitize ]]; then
  shift
  dir=build-sanitize
  config=(-DCMAKE_BUILD_TYPE=Debug -DVOXSPAN_SANITIZE=ON)
fi
cmake -S . -B "$dir" "${config[@]}" -DVOXSPAN_WERROR=ON "$@" >/dev/null
cmake --build "$dir" -j"$(nproc)"
