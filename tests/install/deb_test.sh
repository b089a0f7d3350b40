#!/usr/bin/env bash
# deb_test.sh BUILD_DIR VERSION CPACK — cpack -G DEB into a temporary folder (nothing left in the build
# folder), then the package's files and control fields.
set -euo pipefail
build=$1 version=$2 cpack=$3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "deb_test: $*" >&2; exit 1; }

(cd "$tmp" && "$cpack" -G DEB --config "$build/CPackConfig.cmake" -B "$tmp/out" >"$tmp/cpack.log" 2>&1) ||
  { cat "$tmp/cpack.log"; fail "cpack failed"; }
deb=$(ls "$tmp"/out/contactlab_"$version"_*.deb) || fail "no contactlab_${version}_*.deb made"
dpkg-deb -I "$deb"
dpkg-deb -c "$deb" >"$tmp/files.txt"
for f in ./usr/bin/contactlab ./usr/lib/udev/rules.d/70-contactlab.rules ./usr/share/contactlab/scenes/block.json \
         ./usr/share/contactlab/scenes/experiments/003-curvature.json ./usr/share/doc/contactlab/README.md \
         ./usr/lib/cmake/ContactLab/ContactLabConfig.cmake ./usr/include/haptics/proxy.hpp; do
  grep -q " $f\$" "$tmp/files.txt" || fail "$f is not in the package"
done
depends=$(dpkg-deb -f "$deb" Depends)
for d in libvulkan1 libglfw3 libusb-1.0-0 mesa-vulkan-drivers; do
  grep -q "$d" <<<"$depends" || fail "Depends lacks $d: $depends"
done
echo "deb_test: ok ($(stat -c %s "$deb") bytes)"
