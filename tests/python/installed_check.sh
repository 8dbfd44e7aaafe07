#!/bin/sh
# installed_check.sh BUILD_DIR WORK_DIR PYTHON MODULE_DIR: installs the build into
# WORK_DIR/prefix, then imports voxspan from the prefix's MODULE_DIR (relative to the prefix,
# VOXSPAN_PYTHON_INSTALL_DIR) and renders a block of particles, as a user of the installed
# package would, from a folder without the build tree on its path.
set -eu
build=$1; work=$2; python=$3; module_dir=$4
rm -rf "$work"; mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cd "$work"
PYTHONPATH="$work/prefix/$module_dir" "$python" -c "
import numpy, voxspan, sys
assert voxspan.__file__.startswith('$work/prefix/'), voxspan.__file__
block = numpy.mgrid[0:10, 0:10, 0:10].reshape(3, -1).T * 0.1
picture = voxspan.render(block, output='out')['main']
assert picture.shape[2] == 4 and picture.std() > 0
print('installed module OK:', voxspan.__file__)
"
