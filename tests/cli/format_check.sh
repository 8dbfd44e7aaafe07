#!/bin/sh
# format_check.sh SOURCE_DIR: every C and C++ file of the project follows its .clang-format
# (clang-format --dry-run --Werror names each line that does not).
set -eu
cd "$1"
find sim_adapter render insitu python tools tests examples \
     \( -name '*.cpp' -o -name '*.h' -o -name '*.c' \) -print0 |
  xargs -0 clang-format --dry-run --Werror
echo "format OK"
