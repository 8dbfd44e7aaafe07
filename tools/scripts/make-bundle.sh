#!/bin/bash
# tools/scripts/make-bundle.sh [OUT_DIR] - a lean Release build of the command-line tools, with the
# non-system shared libraries they need, in one folder that runs on a GPU machine without a
# package manager:  OUT_DIR/bin/<tool>  (RPATH $ORIGIN/../lib)  and  OUT_DIR/lib/*.so*,
# and the same folder as OUT_DIR.tar.gz, one file to copy. Only the tools device-check.sh runs go
# in (see below). tools/scripts/device-check.sh runs from either.
#
# Left out on purpose, because the target machine must provide its own:
#   glibc (libc, libm, ld-linux...), libstdc++ and libgcc_s (a newer system copy is backward
#   compatible, an older carried one would break the driver's libraries), and the GL vendor-
#   neutral dispatch of libglvnd (libEGL, libGL, libOpenGL, libGLX, libGLdispatch), which must be
#   the machine's so that it finds the NVIDIA driver.
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(realpath -m "${1:-bundle}")
build=build-bundle

tools/scripts/setup.sh
# DT_RPATH (not RUNPATH) so that the carried libraries' own dependencies resolve from lib/ too.
# The examples' WCSPH solver goes in for bench_insitu (the in-situ cost on the GPU machine).
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DVOXSPAN_BUILD_TESTS=OFF \
  -DVOXSPAN_BUILD_EXAMPLES=ON -DCMAKE_INSTALL_RPATH='$ORIGIN/../lib' \
  -DCMAKE_EXE_LINKER_FLAGS='-Wl,--disable-new-dtags' >/dev/null
cmake --build "$build" -j"$(nproc)"
rm -rf "$out"
cmake --install "$build" --prefix "$out" --strip >/dev/null
rm -rf "$out/include" "$out/lib/cmake"
# Only the tools tools/scripts/device-check.sh runs (read from it, so the list is written once)
# and their libraries: the others carry Embree and VTK, which took the archive past 64 MiB.
keep=$(grep -o '\$bin/[A-Za-z_-]*' tools/scripts/device-check.sh | sed 's/^\$bin\///' | sort -u)
for exe in "$out"/bin/*; do
  grep -qx "$(basename "$exe")" <<<"$keep" || rm -f "$exe"
done

system_lib='^(linux-vdso|ld-linux|libc|libm|libdl|libpthread|librt|libresolv|libstdc\+\+|libgcc_s|libEGL|libGL|libGLX|libOpenGL|libGLdispatch)\.so'
for exe in "$out"/bin/*; do
  ldd "$exe" | awk '$3 ~ /^\// { print $1, $3 }' | while read -r name path; do
    [[ $name =~ $system_lib ]] && continue
    [[ -e $out/lib/$name ]] || cp -L "$path" "$out/lib/$name"
  done
done
tar -C "$(dirname "$out")" -czf "$out.tar.gz" "$(basename "$out")"
echo "bundle: $out ($(du -sh "$out" | cut -f1)), $out.tar.gz ($(du -sh "$out.tar.gz" | cut -f1)):" \
  "$(ls "$out/bin" | tr '\n' ' ')"
