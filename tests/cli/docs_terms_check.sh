#!/bin/sh
# docs_terms_check.sh SOURCE_DIR: the user's documents (README.md, docs/, examples/) call the
# particles of the fluid's outer cells "surface-shell particles", never "boundary particles":
# PySPH and most SPH codes call their wall particles that (an array named `boundary`). Names
# each file and the words, also where a line break splits them.
set -eu
cd "$1"
status=0
for f in README.md docs/*.md $(find examples -name '*.md' -o -name '*.yaml'); do
  # One line per file, comment marks dropped, so that words split over lines are found.
  hits=$(sed 's/^[[:space:]]*#//' "$f" | tr '\n' ' ' |
         grep -oiE 'boundary[[:space:]]+(particles?|spheres)' || true)
  if [ -n "$hits" ]; then
    echo "$f: $(echo "$hits" | tr '\n' ';')"
    status=1
  fi
done
[ $status -eq 0 ] && echo "terms OK"
exit $status
