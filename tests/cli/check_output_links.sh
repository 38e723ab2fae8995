#!/usr/bin/env bash
# check_output_links.sh — probe F5: a symbolic link under one of a run's
# file names (stats.csv, biaxial.csv, or a temporary such as
# .frames.pvd.tmp) in a marked output directory made the next run append to
# (or truncate) the link's target outside the directory, with exit 0. Now
# the run is refused before it writes anything (exit 2, one line naming the
# link), and the target is unchanged.
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_check_links.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1

cat >scene.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 20}
materials: [{name: glass, density: 2500, youngs_modulus: 1.0e7}]
walls: [{name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}]
particles: [{generator: list, material: glass, spheres: [{position: [0, 0, 0.01], radius: 0.001}]}]
output: {every: 10, stats_every: 5}
EOF

# case NAME SCENE STEPS: a first run, a link NAME -> the user's file, a second run
link_case() {
    local name=$1 scene=$2 steps=$3
    rm -rf out mine.csv
    printf 'my,own,results\n1,2,3\n' >mine.csv
    local before
    before=$(cksum <mine.csv)
    "$bin" run "$scene" -o out --steps "$steps" -q
    check "$name: first run exits 0" "$([[ $? == 0 ]] && echo 1 || echo 0)"
    rm -f "out/$name"
    ln -s "$tmp/mine.csv" "out/$name"
    "$bin" run "$scene" -o out --steps "$steps" -q 2>err.txt
    local rc=$?
    check "$name: second run refused with exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
    check "$name: one stderr line naming the link ($(head -c 160 err.txt))" \
        "$([[ $(wc -l <err.txt) == 1 ]] && grep -q "out/$name.*symbolic link" err.txt && echo 1 || echo 0)"
    check "$name: the link's target is unchanged" "$([[ $(cksum <mine.csv) == "$before" ]] && echo 1 || echo 0)"
    check "$name: the link itself is left" "$([[ -L out/$name ]] && echo 1 || echo 0)"
}
link_case stats.csv scene.yaml 20
link_case .frames.pvd.tmp scene.yaml 20
link_case biaxial.csv "$root/examples/biaxial-2d.yaml" 10

finish check_output_links
