#!/usr/bin/env bash
# restart_scene_edits.sh — a restart refuses a checkpoint of another scene
# and names what differs (issue 31, probe 3 finding 3: 15 of 24 edits used
# to run, exit 0). restart_scenes/edits.yaml (a rotating mesh drum, an
# insertion, an outlet) and the same scene with an analytic drum each
# write a step-100 checkpoint; then one setting at a time is edited and
# the run restarted from it: every edit of the physics (mesh rpm, axis,
# motion, position, scale, file, side; insertion count, size, region, the
# insertion or the outlets deleted, the outlet region; the drum's radius,
# rpm, length, centre; gravity, density, dt) exits 2 with "written by
# another scene" and the part that differs, and writes no output
# directory; the edits docs/checkpoints.md allows (start particles,
# max_overlap, output cadence, threads) run on, exit 0.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
src=$root/tests/cli/restart_scenes
cp "$src/edits.yaml" "$src/drum.stl" "$tmp/"
cd "$tmp" || exit 1
# another file with one vertex moved by a few nanometres (a low byte of
# facet 1's first x coordinate)
cp drum.stl drum-b.stl
chmod u+w drum-b.stl
printf '\x01' | dd of=drum-b.stl bs=1 seek=96 conv=notrunc 2>/dev/null
# the analytic-drum scene: the mesh wall replaced by a drum of its size
drum_wall='  - {name: drum, type: drum, center: [0, 0, 0], axis: [0, 1, 0], radius: 0.03, length: 0.02, rpm: 30, material: glass}'
sed "s|^  - {name: drum, type: mesh.*|$drum_wall|" edits.yaml >drum.yaml

for base in edits drum; do
    "$bin" run $base.yaml -o "base-$base" --quiet --threads 1 >"base-$base.out" 2>&1
    rc=$?
    check "$base.yaml writes its step-100 checkpoint (exit $rc)" \
        "$([[ $rc == 0 && -f base-$base/checkpoint-000100.h5 ]] && echo 1 || echo 0)"
done

n=0
# refused BASE PART SED-SCRIPT: the edited scene's restart exits 2 naming PART
refused() {
    local base=$1 part=$2 edit=$3
    n=$((n + 1))
    sed "s/steps: 100/steps: 110/; $edit" $base.yaml >e$n.yaml
    if cmp -s $base.yaml e$n.yaml; then
        check "edit $n ($edit) changes the scene" 0
        return
    fi
    "$bin" run e$n.yaml --restart "base-$base/checkpoint-000100.h5" -o "out$n" --quiet >e$n.out 2>&1
    local rc=$?
    local msg
    msg=$(cat e$n.out)
    check "$base: $edit: exit 2 (got $rc), names $part" \
        "$([[ $rc == 2 && $msg == *"written by another scene"* && $msg == *"$part"* ]] && echo 1 || echo 0)" "$msg"
    check "$base: $edit: no output directory" "$([[ ! -e out$n ]] && echo 1 || echo 0)"
}
# allowed BASE SED-SCRIPT [OPTION...]: the edited scene restarts, exit 0
allowed() {
    local base=$1 edit=$2
    shift 2
    n=$((n + 1))
    sed "s/steps: 100/steps: 110/; $edit" $base.yaml >e$n.yaml
    "$bin" run e$n.yaml --restart "base-$base/checkpoint-000100.h5" -o "out$n" --quiet "$@" >e$n.out 2>&1
    local rc=$?
    check "$base: allowed $edit $*: exit 0 (got $rc)" "$((rc == 0))" "$(cat e$n.out)"
}

mesh="the mesh walls"
refused edits "$mesh" 's/rpm: 30/rpm: 300/'
refused edits "$mesh" 's/axis: \[0, 1, 0\], rpm/axis: [1, 0, 0], rpm/'
refused edits "$mesh" 's/, motion: {type: rotate[^}]*}//'
refused edits "$mesh" 's/file: drum.stl,/file: drum.stl, position: [0, 0.001, 0],/'
refused edits "$mesh" 's/file: drum.stl,/file: drum.stl, scale: 1.1,/'
refused edits "$mesh" 's/file: drum.stl,/file: drum.stl, rotation: [0, 10, 0],/'
refused edits "$mesh" 's/file: drum.stl,/file: drum-b.stl,/'
refused edits "$mesh" 's/file: drum.stl,/file: drum.stl, side: outside,/'
refused edits "the insertions" 's/count: 30,/count: 300,/'
refused edits "the insertions" 's/max: 0.0012/max: 0.0011/'
refused edits "the insertions" 's/max: \[0.01, 0.005, 0.01\]/max: [0.01, 0.005, 0.012]/'
refused edits "the insertions" 's/rate: 20000/rate: 10000/'
refused edits "the insertions" '/^insert:/,+1d'
refused edits "the outlets" '/^outlets:/,+1d'
refused edits "the outlets" 's/max: \[0.005, 0.01, -0.028\]/max: [0.006, 0.01, -0.028]/'
refused edits "the simulation settings" 's/seed: 9/seed: 9, gravity: [0, 0, 9.81]/'
refused edits "the simulation settings" 's/dt: 1.0e-5/dt: 0.9e-5/'
refused edits "the materials" 's/density: 2500/density: 2600/'
refused edits "the shape templates" 's/length: 0.004/length: 0.0041/'
walls="the walls"
refused drum "$walls" 's/radius: 0.03,/radius: 0.031,/'
refused drum "$walls" 's/length: 0.02,/length: 0.021,/'
refused drum "$walls" 's/center: \[0, 0, 0\]/center: [0, 0.001, 0]/'
refused drum "$walls" 's/rpm: 30/rpm: 31/'

allowed edits 's/count: \[5, 3, 3\]/count: [4, 3, 3]/'
allowed edits 's/seed: 9/seed: 9, max_overlap: 0.6/'
allowed edits 's/every: 100, stats_every: 50/every: 5, stats_every: 2/'
allowed edits '' --threads 2
allowed drum 's/checkpoint_every: 100/checkpoint_every: 5/'
finish
