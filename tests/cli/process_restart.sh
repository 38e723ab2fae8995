#!/usr/bin/env bash
# process_restart.sh — insertion into a mesh region with scaled template
# copies restarts bit for bit (issue 16 with issue 17's checkpoints):
# process_scenes/mesh-feed.yaml (spheres and log-normal cubes fed at
# 20,000/s into an L-shaped mesh region) run straight through on 2 threads,
# and again from its step-400 checkpoint on 1 thread, writes the same last
# frame, byte for byte, and the same insertion line in summary.txt.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene=$root/tests/cli/process_scenes/mesh-feed.yaml

"$bin" run "$scene" --threads 2 --quiet -o "$tmp/a" >"$tmp/a.out" 2>&1
rc=$?
check "straight run: exit 0 (got $rc)" "$((rc == 0))"
"$bin" run "$scene" --threads 1 --quiet -o "$tmp/b" --restart "$tmp/a/checkpoint-000400.h5" >"$tmp/b.out" 2>&1
rc=$?
check "run resumed at step 400: exit 0 (got $rc)" "$((rc == 0))"
cat "$tmp/b.out"
ins_a=$(grep "^insert feed:" "$tmp/a/summary.txt")
ins_b=$(grep "^insert feed:" "$tmp/b/summary.txt")
echo "     straight: $ins_a"
echo "     resumed:  $ins_b"
check "the same insertion record (asked, inserted, mass)" "$([[ -n $ins_a && $ins_a == "$ins_b" ]] && echo 1 || echo 0)"
# the straight run's frames are 0, 400, 800; the resumed run's 400, 800
cmp -s "$tmp/a/particles_000002.vtu" "$tmp/b/particles_000001.vtu"
check "the last frame (step 800) is the same, byte for byte" "$((! $?))"
finish
