#!/bin/bash
# tools/test.sh [--no-sanitize | --sanitize-only] - the test command of the README and of CI:
# installs what is missing, builds with warnings as errors and runs every test (GL tests on
# llvmpipe when there is no GPU), first in the Release build, then in the sanitizer build
# (AddressSanitizer with leak checks + UndefinedBehaviorSanitizer; docs/testing.md).
# --no-sanitize skips the second suite (a quick local run); --sanitize-only skips the first.
set -euo pipefail
cd "$(dirname "$0")/.."
release=1 sanitize=1
case ${1:-} in
  "") ;;
  --no-sanitize) sanitize=0 ;;
  --sanitize-only) release=0 ;;
  *) echo "usage: tools/test.sh [--no-sanitize | --sanitize-only]" >&2; exit 2 ;;
esac
tools/scripts/setup.sh
# Open MPI refuses to run as root without these (CI runs as root).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# PySPH's dam break (test_default_view_pysph; about 25 s, Python) runs once for both suites.
VOXSPAN_PYSPH_OUTPUT=$(mktemp -d)
export VOXSPAN_PYSPH_OUTPUT
trap 'rm -rf "$VOXSPAN_PYSPH_OUTPUT"' EXIT
if ((release)); then
  tools/scripts/build.sh
  ctest --test-dir build --output-on-failure -j"$(nproc)"
fi
if ((sanitize)); then
  echo "test: the sanitizer build (build-sanitize/)"
  tools/scripts/build.sh --sanitize
  (. tests/sanitizers/options.sh && ctest --test-dir build-sanitize --output-on-failure -j"$(nproc)")
fi
