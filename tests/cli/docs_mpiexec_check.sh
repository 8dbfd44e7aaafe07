#!/bin/sh
# docs_mpiexec_check.sh SOURCE_DIR: every `mpiexec -n N` with N over 2 that README.md, docs/ and
# examples/ show carries --oversubscribe: without it Open MPI stops with "not enough slots" on
# a 2-core machine, where the project is built and tested. Names each line that does not.
set -eu
cd "$1"
bad=$(grep -rnE 'mpiexec[^`]* -n +([3-9]|[1-9][0-9]+)' README.md docs examples \
        --include='*.md' --include='*.yaml' --include='*.sh' | grep -v -- '--oversubscribe' || true)
if [ -n "$bad" ]; then
  echo "mpiexec with more than 2 ranks and no --oversubscribe:"
  echo "$bad"
  exit 1
fi
echo "mpiexec examples OK"
