#!/usr/bin/env bash
# scene_from.sh — a scene that starts from a checkpoint of another run
# (generator: csv, file: a .h5 checkpoint; io/scene_from.c), from the
# command line: a bed of spheres and bricks settles with checkpoint_every,
# a new scene with other walls and a shift starts from its checkpoint and
# runs; bad starts are refused with exit 2, one stderr line naming the
# scene file, the line of file: and the key particles[0].file, and no
# output directory: a missing file, a template this scene lacks, a
# template of another kind, a damaged checkpoint (one byte flipped, cut
# short), a checkpoint of the other dimension. A bed poured by an insertion
# with a size law (scaled copies of its brick) starts a new scene too (also
# one with an insertion of bricks of its own, which restarts bit for bit),
# and is refused where the new scene lacks the brick or has it of another
# kind.
set -u
exe=${1:?usage: scene_from.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_scene_from.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish

head_yaml() { # the physics both scenes share; $1 = the brick's type line
    cat <<EOF
simulation: {dt: 1.0e-5, steps: 3000, gravity: [0, 0, -9.81], seed: 4}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, friction: 0.5, restitution: 0.5}
shapes:
  - {name: brick, $1}
EOF
}
{
    head_yaml "type: box, size: [0.002, 0.003, 0.004]"
    cat <<EOF
particles:
  - {generator: random, material: glass, radius: 0.0012, number: 60, box: {min: [0, 0, 0], max: [0.02, 0.02, 0.02]}}
  - {generator: random, material: glass, shape: brick, number: 20, box: {min: [0, 0, 0.021], max: [0.02, 0.02, 0.05]}}
walls:
  - {name: cup, type: box, min: [0, 0, 0], max: [0.02, 0.02, 0.08], open: [zmax], material: glass}
output: {every: 3000, checkpoint_every: 3000}
EOF
} >"$tmp/bed.yaml"
(cd "$tmp" && "$exe" run bed.yaml -o bed --threads 1 >/dev/null 2>"$tmp/bed.err")
check "the bed runs and writes bed/checkpoint-003000.h5 ($(cat "$tmp/bed.err"))" \
    "$([[ -s $tmp/bed/checkpoint-003000.h5 ]] && echo 1 || echo 0)"

from_yaml() { # $1 = the brick's type line, $2 = the file
    head_yaml "$1"
    cat <<EOF
particles:
  - generator: csv
    material: glass
    file: $2
    shift: [0.1, 0, 0.001]
walls:
  - {name: floor, type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
EOF
}
from_yaml "type: box, size: [0.002, 0.003, 0.004]" bed/checkpoint-003000.h5 >"$tmp/new.yaml"
(cd "$tmp" && "$exe" run new.yaml -o new --steps 500 --threads 1 >"$tmp/new.out" 2>"$tmp/new.err")
rc=$?
check "the new scene runs from the checkpoint (exit $rc: $(cat "$tmp/new.err"))" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
check "it has the bed's 80 particles ($(head -1 "$tmp/new.out"))" \
    "$(grep -q '^shapedem: 80 particles, 500 steps' "$tmp/new.out" && echo 1 || echo 0)"

# damaged copies
cp "$tmp/bed/checkpoint-003000.h5" "$tmp/flipped.h5"
size=$(stat -c %s "$tmp/flipped.h5")
at=$((size / 2))
byte=$(od -An -tu1 -j "$at" -N1 "$tmp/flipped.h5" | tr -d ' ')
printf "$(printf '\\%03o' $(((byte + 1) % 256)))" | dd of="$tmp/flipped.h5" bs=1 seek="$at" conv=notrunc 2>/dev/null
head -c $((size - 4096)) "$tmp/bed/checkpoint-003000.h5" >"$tmp/short.h5"
# a planar checkpoint
cat >"$tmp/flat.yaml" <<EOF
simulation: {dimension: 2, dt: 1.0e-5, steps: 10, gravity: [0, -9.81, 0]}
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, friction: 0.5}
shapes:
  - {name: brick, type: circle, radius: 0.002}
particles:
  - {generator: random, material: glass, shape: brick, number: 10, box: {min: [0, 0, -0.01], max: [0.05, 0.05, 0.01]}}
output: {every: 10, checkpoint_every: 10}
EOF
(cd "$tmp" && "$exe" run flat.yaml -o flat --threads 1 >/dev/null 2>&1)

bad() { # bad NAME WHAT-THE-MESSAGE-SAYS (a grep -E pattern); the scene is $tmp/bad.yaml
    rm -rf "$tmp/out"
    (cd "$tmp" && "$exe" run bad.yaml -o out --threads 1 >/dev/null 2>"$tmp/bad.err")
    local rc=$? err
    err=$(cat "$tmp/bad.err")
    echo "  $1: exit $rc: $err"
    check "$1: exit 2" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
    check "$1: one line naming bad.yaml:9: particles[0].file" \
        "$([[ $(wc -l <"$tmp/bad.err") == 1 ]] && grep -q 'bad.yaml:9: particles\[0\]\.file: ' "$tmp/bad.err" &&
            echo 1 || echo 0)"
    check "$1: says why" "$(grep -Eq "$2" "$tmp/bad.err" && echo 1 || echo 0)"
    check "$1: no output directory" "$([[ ! -e $tmp/out ]] && echo 1 || echo 0)"
}
from_yaml "type: box, size: [0.002, 0.003, 0.004]" bed/checkpoint-000000.h5 >"$tmp/bad.yaml"
bad "a missing checkpoint" "cannot start from the checkpoint 'bed/checkpoint-000000.h5': .*(No such file|cannot open)"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" flipped.h5 >"$tmp/bad.yaml"
bad "a byte flipped" "cannot start from the checkpoint 'flipped.h5': .*damaged"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" short.h5 >"$tmp/bad.yaml"
bad "cut short by 4 KiB" "cannot start from the checkpoint 'short.h5': .*(truncated|damaged|size)"
from_yaml "type: cylinder, diameter: 0.002, length: 0.004" bed/checkpoint-003000.h5 >"$tmp/bad.yaml"
bad "a template of another kind" "template 'brick' is a box there, a cylinder in this scene"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" bed/checkpoint-003000.h5 | sed 's/name: brick/name: block/' >"$tmp/bad.yaml"
bad "a template this scene lacks" "template 'brick', which this scene's shapes: does not define \(shapes: block\)"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" flat/checkpoint-000010.h5 >"$tmp/bad.yaml"
bad "a planar checkpoint in a 3D scene" "is of a 2D run, this scene is 3D"

# a bed poured by an insertion with a size law: its bricks are scaled copies
# (brick_i0e0sK, world/scaled.c), made again from the new scene's brick
{
    head_yaml "type: box, size: [0.002, 0.003, 0.004]"
    cat <<EOF
insert:
  - {name: fill, region: box, min: [0, 0, 0.001], max: [0.02, 0.02, 0.02], count: 20, attempts: 500,
     velocity: [0, 0, -0.5],
     mix: [{material: glass, shape: brick, distribution: uniform, radius: {min: 0.0012, max: 0.0016}, size_classes: 3}]}
walls:
  - {name: cup, type: box, min: [0, 0, 0], max: [0.02, 0.02, 0.08], open: [zmax], material: glass}
output: {every: 200, checkpoint_every: 200}
EOF
} >"$tmp/poured.yaml"
(cd "$tmp" && "$exe" run poured.yaml -o poured --steps 200 --threads 1 >/dev/null 2>"$tmp/poured.err")
check "the poured bed writes poured/checkpoint-000200.h5 ($(cat "$tmp/poured.err"))" \
    "$([[ -s $tmp/poured/checkpoint-000200.h5 ]] && echo 1 || echo 0)"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" poured/checkpoint-000200.h5 >"$tmp/copies.yaml"
(cd "$tmp" && "$exe" run copies.yaml -o copies --steps 100 --threads 1 >"$tmp/copies.out" 2>"$tmp/copies.err")
rc=$?
check "a new scene runs from the scaled copies (exit $rc: $(cat "$tmp/copies.err"))" \
    "$([[ $rc == 0 ]] && grep -q '^shapedem: 20 particles, 100 steps' "$tmp/copies.out" && echo 1 || echo 0)"
{
    from_yaml "type: box, size: [0.002, 0.003, 0.004]" poured/checkpoint-000200.h5
    cat <<EOF
insert:
  - {name: more, region: box, min: [0.1, 0, 0.03], max: [0.12, 0.02, 0.05], count: 10, attempts: 500,
     mix: [{material: glass, shape: brick, distribution: uniform, radius: {min: 0.0012, max: 0.0016}, size_classes: 3}]}
EOF
} >"$tmp/more.yaml"
(cd "$tmp" && "$exe" run more.yaml -o more --steps 100 --threads 1 >"$tmp/more.out" 2>"$tmp/more.err")
rc=$?
check "with an insertion of its own, whose copies take the next free names (exit $rc: $(cat "$tmp/more.err"))" \
    "$([[ $rc == 0 ]] && grep -q '^shapedem: 30 particles, 100 steps' "$tmp/more.out" && echo 1 || echo 0)"
# that scene restarts bit for bit (its copies made again from the same file)
{
    cat "$tmp/more.yaml"
    echo "output: {every: 100, checkpoint_every: 50}"
} >"$tmp/again.yaml"
(cd "$tmp" && "$exe" run again.yaml -o again1 --steps 100 --threads 1 >/dev/null 2>&1 &&
    "$exe" run again.yaml -o again2 --until-step 100 --threads 2 --restart again1/checkpoint-000050.h5 >/dev/null 2>&1)
sum1=$(cd "$tmp" && "$exe" info again1/checkpoint-000100.h5 2>&1 | grep '^checksum')
sum2=$(cd "$tmp" && "$exe" info again2/checkpoint-000100.h5 2>&1 | grep '^checksum')
check "restarted at step 50 on 2 threads, its step-100 checkpoint is the straight run's ($sum1 / $sum2)" \
    "$([[ -n $sum1 && $sum1 == "$sum2" ]] && echo 1 || echo 0)"
from_yaml "type: box, size: [0.002, 0.003, 0.004]" poured/checkpoint-000200.h5 |
    sed 's/name: brick/name: block/' >"$tmp/bad.yaml"
bad "a scaled copy whose template this scene lacks" \
    "template 'brick_i0e0s[0-9]', a copy of 'brick' scaled by [0-9.e-]+ that an insertion made; this scene's shapes: does not define 'brick' \(shapes: block\)"
from_yaml "type: cylinder, diameter: 0.002, length: 0.004" poured/checkpoint-000200.h5 >"$tmp/bad.yaml"
bad "a scaled copy whose template is of another kind" \
    "template 'brick_i0e0s[0-9]' is a copy of 'brick' scaled by [0-9.e-]+, and 'brick' is a box there, a cylinder in this scene"

finish
