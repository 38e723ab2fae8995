#!/usr/bin/env bash
# scene_example.sh — the scene-loading C example (examples/c/run_scene.c)
# builds against the build tree's library (public headers only: -I include,
# never src/) and runs a short copy of examples/settle-spheres.yaml; the
# library run and `shapedem run` of the same scene cannot be told apart:
# the same particle count and kinetic energy, and byte-identical stats.csv
# and frames (both go through the public run API, include/shapedem/scene.h).
#
# Usage: bash scene_example.sh /path/to/shapedem /path/to/repo
set -u
bin="$1"
root=$(cd "$2" && pwd)
build=$(cd "$(dirname "$bin")" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_scene_example.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

lib=
for f in "$build"/libshapedem.so "$build"/libshapedem.a; do [[ -z $lib && -e $f ]] && lib=$f; done
check "the build tree has the library ($lib)" "$([[ -n $lib ]] && echo 1 || echo 0)"
if [[ $lib == *.so ]]; then
    link=(-L"$build" -lshapedem -Wl,-rpath,"$build")
else # a static-only build: its dependencies by hand
    link=("$lib" -lyaml -lm -fopenmp)
fi
# a sanitizer build's library (make test-sanitize) needs its runtime first
# in the program: the example is built with the same sanitizers
san=()
if [[ $lib == *.so ]] && ldd "$lib" 2>/dev/null | grep -q 'libasan'; then
    san=(-fsanitize=address,undefined)
fi
cc -std=c17 -Wall -Wextra -Werror -pedantic "${san[@]}" -I"$root/include" "$root/examples/c/run_scene.c" \
    "${link[@]}" -o "$tmp/run_scene" >"$tmp/cc.log" 2>&1
rc=$?
check "examples/c/run_scene.c compiles against include/ and the library (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
((rc == 0)) || head -5 "$tmp/cc.log"

# the example scene, 300 steps, output every 100 (stats every 50)
sed -e 's/^  duration: .*/  steps: 300/' -e 's/^  every: .*/  every: 100/' -e 's/^  stats_every: .*/  stats_every: 50/' \
    -e 's|^  directory: .*|  directory: unused|' "$root/examples/settle-spheres.yaml" >"$tmp/settle.yaml"
check "the short scene has 300 steps" "$(grep -q '^  steps: 300' "$tmp/settle.yaml" && echo 1 || echo 0)"

OMP_NUM_THREADS=2 "$tmp/run_scene" "$tmp/settle.yaml" "$tmp/lib" >"$tmp/lib.out" 2>&1
rc=$?
check "run_scene exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
((rc == 0)) || head -5 "$tmp/lib.out"
n_lib=$(sed -n 's/^particles \([0-9]*\)$/\1/p' "$tmp/lib.out")
ke_lib=$(sed -n 's/^kinetic_energy \([^ ]*\) J$/\1/p' "$tmp/lib.out")
check "run_scene prints 2028 particles (got '$n_lib')" "$([[ $n_lib == 2028 ]] && echo 1 || echo 0)"
for f in frames.pvd stats.csv summary.txt; do
    check "run_scene wrote $f" "$([[ -s $tmp/lib/$f ]] && echo 1 || echo 0)"
done
rows=$(($(wc -l <"$tmp/lib/stats.csv") - 1))
check "stats.csv has the rows of steps 0, 50, ..., 300 (7, got $rows)" "$([[ $rows == 7 ]] && echo 1 || echo 0)"
frames=$(grep -c '<DataSet ' "$tmp/lib/frames.pvd")
check "frames.pvd lists the frames of steps 0, 100, 200, 300 (got $frames)" "$([[ $frames -ge 4 ]] && echo 1 || echo 0)"

OMP_NUM_THREADS=2 "$bin" run "$tmp/settle.yaml" -o "$tmp/cli" >"$tmp/cli.out" 2>&1
rc=$?
check "shapedem run of the same scene exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
ke_cli=$(sed -n 's/.*kinetic energy \([^ ]*\) J.*/\1/p' "$tmp/cli.out")
ke_lib6=$(printf '%.6g' "$ke_lib" 2>/dev/null)
check "the same kinetic energy: library $ke_lib6 J (%.6g of $ke_lib), CLI $ke_cli J" \
    "$([[ -n $ke_cli && $ke_lib6 == "$ke_cli" ]] && echo 1 || echo 0)"
check "the same stats.csv, byte for byte" "$(cmp -s "$tmp/lib/stats.csv" "$tmp/cli/stats.csv" && echo 1 || echo 0)"
same=1
for f in "$tmp"/lib/*.vtu; do
    cmp -s "$f" "$tmp/cli/$(basename "$f")" || same=0
done
check "the same particle frames, byte for byte" "$same"

# bad input through the library: one message naming the file, exit 2
printf 'simulation: {dt: 1.0e-5, steps: 10}\nmaterials: [{name: m, density: -1}]\n' >"$tmp/bad.yaml"
"$tmp/run_scene" "$tmp/bad.yaml" "$tmp/bad" >"$tmp/bad.out" 2>&1
rc=$?
check "a bad scene: exit 2 and the file:line: key (got $rc: $(head -1 "$tmp/bad.out"))" \
    "$([[ $rc == 2 ]] && grep -q 'bad.yaml:2: materials\[0\].density' "$tmp/bad.out" && echo 1 || echo 0)"
check "a bad scene writes nothing" "$([[ ! -e $tmp/bad ]] && echo 1 || echo 0)"

finish
