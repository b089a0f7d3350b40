#!/usr/bin/env bash
# install_test.sh BUILD_DIR EXAMPLES_DIR VERSION CMAKE CXX — see CMakeLists.txt beside it.
set -euo pipefail
build=$1 examples=$2 version=$3 cmake=$4 cxx=$5
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix=$tmp/prefix
fail() { echo "install_test: $*" >&2; exit 1; }

"$cmake" --install "$build" --prefix "$prefix" >"$tmp/install.log" || { cat "$tmp/install.log"; fail "cmake --install failed"; }

# The tool runs from the prefix and says which version it is.
out=$("$prefix/bin/contactlab" --version)
echo "$out"
grep -q "$version" <<<"$out" || fail "contactlab --version does not name $version: $out"

for f in share/contactlab/scenes/flat.json share/contactlab/scenes/block.json \
         share/contactlab/scenes/experiments/000-contour-following.json \
         lib/udev/rules.d/70-contactlab.rules \
         share/doc/contactlab/README.md share/doc/contactlab/scenes/README.md share/doc/contactlab/docs/library.md \
         share/doc/contactlab/examples/proxy_path/CMakeLists.txt \
         include/haptics/proxy.hpp include/haptics/wearable/rig.hpp include/drivers/sim/sim_rig.hpp \
         lib/cmake/ContactLab/ContactLabConfig.cmake lib/cmake/ContactLab/ContactLabConfigVersion.cmake \
         lib/cmake/ContactLab/ContactLabTargets.cmake; do
  [ -f "$prefix/$f" ] || fail "missing $f in the installed prefix"
done
[ ! -e "$prefix/include/haptics/verify" ] || fail "the tests' haptics/verify/ headers were installed"

# The installed binary finds its scenes beside it, from any working directory.
(cd "$tmp" && "$prefix/bin/contactlab" demo >"$tmp/demo.txt") || fail "contactlab demo (default scene) failed outside a checkout"
grep -q "share/contactlab/scenes/block.json" "$tmp/demo.txt" || fail "contactlab demo did not read the installed block.json"

# Each example, as a user builds it: its own folder, find_package(ContactLab) from the prefix.
build_example() {
  local name=$1
  "$cmake" -S "$examples/$name" -B "$tmp/$name" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release >"$tmp/$name.log" 2>&1 &&
  "$cmake" --build "$tmp/$name" >>"$tmp/$name.log" 2>&1 || { cat "$tmp/$name.log"; fail "example $name did not build"; }
}

build_example proxy_path
"$tmp/proxy_path/proxy_path" >"$tmp/proxy.txt" || fail "proxy_path failed"
cat "$tmp/proxy.txt"
# Rows: step x_f y_f contact |F| l_d point_x point_y. Free air: no contact, zero force. In contact
# on the floor: F = Ke * depth (1000 N/m, 1 mm at the last step: 1.000 N), l_d = -R phi = -5.2 mm,
# the contact point on the floor (y = 0) straight below x_f.
awk '$1 ~ /^[0-9]+$/ {
       rows++
       if ($4 == 0) { free++; if ($5 != 0) bad = bad "step " $1 ": force " $5 " N in free air\n" }
       else {
         touch++
         depth = 26 - $3
         if ($5 - depth > 0.002 || depth - $5 > 0.002) bad = bad "step " $1 ": |F| " $5 " N, not Ke * depth " depth " mm\n"
         if ($6 + 5.2 > 0.01 || $6 + 5.2 < -0.01) bad = bad "step " $1 ": l_d " $6 " mm, not -5.2\n"
         if ($8 != 0 || $7 - $2 > 0.01 || $2 - $7 > 0.01) bad = bad "step " $1 ": contact point " $7 "," $8 "\n"
         last = $5
       }
     }
     END {
       if (rows != 21) bad = bad "expected 21 steps, got " rows "\n"
       if (free < 1 || touch < 1) bad = bad "expected free air then contact, got " free " free and " touch " in contact\n"
       if (last != 1.000) bad = bad "last force " last " N, expected 1.000\n"
       printf "%s", bad; exit bad != ""
     }' "$tmp/proxy.txt" || fail "proxy_path printed wrong numbers (above)"

build_example servo_sim
"$tmp/servo_sim/servo_sim" >"$tmp/servo.txt" || fail "servo_sim failed"
cat "$tmp/servo.txt"
# Summary: ticks N, in contact M, max |F| F N (limit 1.50 N), ..., state S, faults K
summary=$(grep '^ticks ' "$tmp/servo.txt") || fail "servo_sim printed no summary"
read -r ticks contact force limit faults < <(sed -E 's/^ticks ([0-9]+), in contact ([0-9]+), max \|F\| ([0-9.]+) N \(limit ([0-9.]+) N\).*faults ([0-9]+)$/\1 \2 \3 \4 \5/' <<<"$summary")
awk -v t="$ticks" -v c="$contact" -v f="$force" -v l="$limit" -v k="$faults" 'BEGIN {
  ok = t > 1000 && c > t / 2 && c < t && f > 0.1 && f <= l + 1e-9 && k == 0
  if (!ok) print "servo_sim summary out of range: ticks " t ", in contact " c ", max |F| " f " N, limit " l ", faults " k
  exit !ok }' || fail "servo_sim printed wrong numbers"
echo "install_test: ok"
