#!/usr/bin/env bash
# checkpoint_signals.sh — checkpoints survive interruptions (issue 17):
#  - SIGTERM: `shapedem run` writes a final checkpoint, exits 130 and says
#    where it is; the checkpoint continues with --restart;
#  - kill -9 at random moments (10 trials, checkpoint_every: 100): the last
#    complete checkpoint always loads (`shapedem info`) and restarts, and
#    every frame listed in the directory is complete;
#  - --restart refuses a checkpoint of another scene, and a truncated one,
#    with exit 2 and the reason;
#  - a restarted run's checkpoint holds the same data (checksum) as the
#    uninterrupted run's at the same step.
set -u
bin="$1"
src="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scene="$tmp/chute.yaml"
sed -e 's#^output:#output:\n  checkpoint_every: 100#' "$src/examples/periodic-chute.yaml" >"$scene"
grep -q "checkpoint_every: 100" "$scene" || { echo "FAIL: scene not made"; exit 1; }
sum() { "$bin" info "$1" 2>/dev/null | sed -n 's/^checksum *\([0-9a-f]*\).*/\1/p'; }

# ---- the uninterrupted reference: 400 steps
"$bin" run "$scene" --steps 400 -o "$tmp/ref" --quiet >/dev/null 2>&1
check "reference run exits 0" "$([[ $? == 0 ]] && echo 1 || echo 0)"
ref300=$(sum "$tmp/ref/checkpoint-000300.h5")
ref400=$(sum "$tmp/ref/checkpoint-000400.h5")
check "reference checkpoints at 300 and 400 ($ref300, $ref400)" "$([[ -n $ref300 && -n $ref400 ]] && echo 1 || echo 0)"

# ---- restart from 300 with 2 threads: the same data at 400
"$bin" run "$scene" --until-step 400 -o "$tmp/re" --quiet --threads 2 --restart "$tmp/ref/checkpoint-000300.h5" \
    >/dev/null 2>"$tmp/re.err"
rc=$?
re400=$(sum "$tmp/re/checkpoint-000400.h5")
check "restart from step 300 to 400 exits 0 (got $rc) with the reference's checksum ($re400 = $ref400)" \
    "$([[ $rc == 0 && -n $re400 && $re400 == "$ref400" ]] && echo 1 || echo 0)"
[[ $rc == 0 ]] || cat "$tmp/re.err"

# ---- refusals
"$bin" run "$src/examples/settle-spheres.yaml" --steps 10 -o "$tmp/other" --quiet \
    --restart "$tmp/ref/checkpoint-000300.h5" >/dev/null 2>"$tmp/other.err"
rc=$?
check "another scene's checkpoint: exit 2 (got $rc), 'another scene'" \
    "$([[ $rc == 2 ]] && grep -q "another scene" "$tmp/other.err" && echo 1 || echo 0)"
head -c 20000 "$tmp/ref/checkpoint-000300.h5" >"$tmp/cut.h5"
"$bin" run "$scene" --steps 10 -o "$tmp/cut" --quiet --restart "$tmp/cut.h5" >/dev/null 2>"$tmp/cut.err"
rc=$?
check "truncated checkpoint: exit 2 (got $rc), 'truncated or damaged'" \
    "$([[ $rc == 2 ]] && grep -q "truncated or damaged" "$tmp/cut.err" && echo 1 || echo 0)"
[[ -e "$tmp/cut" ]] && check "no output directory made for a refused restart" 0

# ---- SIGTERM: a final checkpoint
"$bin" run "$scene" --steps 100000000 -o "$tmp/term" --quiet >/dev/null 2>"$tmp/term.err" &
pid=$!
sleep 2
kill -TERM $pid
wait $pid
rc=$?
last=$(sed -n 's/.*continue with: .* --restart \(.*\)$/\1/p' "$tmp/term.err")
check "SIGTERM: exit 130 (got $rc), says where the final checkpoint is ($last)" \
    "$([[ $rc == 130 && -n $last && -f $last ]] && echo 1 || echo 0)"
if [[ -n $last && -f $last ]]; then
    step=$("$bin" info "$last" | sed -n 's/.*step \([0-9]*\),.*/\1/p')
    "$bin" run "$scene" --steps 20 -o "$tmp/term2" --quiet --restart "$last" >/dev/null 2>&1
    check "the final checkpoint (step $step) restarts" "$([[ $? == 0 ]] && echo 1 || echo 0)"
fi

# ---- kill -9 at random moments
good=0
trials=0
for t in $(seq 1 10); do
    d="$tmp/k$t"
    "$bin" run "$scene" --steps 100000000 -o "$d" --quiet >/dev/null 2>&1 &
    pid=$!
    sleep "$(( (RANDOM % 20) + 5 ))e-1"
    kill -9 $pid
    wait $pid 2>/dev/null
    last=$(ls "$d"/checkpoint-*.h5 2>/dev/null | sort | tail -1)
    [[ -n $last ]] || continue # killed before the first checkpoint
    trials=$((trials + 1))
    ok=1
    "$bin" info "$last" >/dev/null 2>&1 || ok=0
    step=$("$bin" info "$last" 2>/dev/null | sed -n 's/.*step \([0-9]*\),.*/\1/p')
    "$bin" run "$scene" --until-step $((step + 10)) -o "$d-re" --quiet --restart "$last" >/dev/null 2>&1 || ok=0
    for f in "$d"/particles_*.vtu; do
        [[ -e $f ]] || continue
        tail -c 20 "$f" | grep -q "</VTKFile>" || ok=0
    done
    [[ $ok == 1 ]] && good=$((good + 1))
    [[ $ok == 1 ]] || echo "  trial $t: $last (step $step) failed"
done
echo "kill -9: $trials trials with a checkpoint written, $good loaded and restarted with every frame complete"
check "kill -9: the last checkpoint loads and restarts in every trial ($good of $trials, at least 5 trials)" \
    "$([[ $trials -ge 5 && $good == "$trials" ]] && echo 1 || echo 0)"

finish
