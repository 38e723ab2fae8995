#!/usr/bin/env bash
# restart_steps.sh — the end of a run on the command line, and stopping one
# (issue 31, probe 3 finding 2):
#  - `--restart CK --steps N` runs N more steps from the checkpoint's step,
#    and reports them (summary.txt steps_run and start_step, the "N steps"
#    line); --until-step S and --until-time T end at an absolute step or time;
#  - an end before the checkpoint's step is refused (exit 2, one line) and
#    leaves every file of the run as it was (the probe: later frames deleted,
#    CSV files cut, exit 0); two ends at once are refused;
#  - SIGINT acts after the step in progress, not at the next output (the
#    scene writes one frame at its end only), and the hint is the whole
#    command: followed literally it continues the run in the same directory;
#  - every command takes --help; --backend cuda on a build without CUDA names
#    the option, and a scene's backend: cuda its own line;
#  - `check` of steps: 9223372036854775807 says how long, without overflow.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
{ cat "$(dirname "${BASH_SOURCE[0]}")/output_scenes/box27.yaml"; cat <<'EOF'; } >"$tmp/s.yaml"
insert: [{name: f, region: box, min: [0.003, 0.003, 0.02], max: [0.017, 0.017, 0.04], count: 20, rate: 20000, mix: [{material: g, radius: 0.0008}]}]
analysis: [{type: coordination}]
output: {every: 50, stats_every: 10, checkpoint_every: 50}
EOF
listing() { (cd "$1" && for f in * .[a-z]*; do [[ -e $f ]] && echo "$f $(cksum <"$f")"; done); }

# ---- the reference run, then ends in the past: refused, nothing touched
"$bin" run "$tmp/s.yaml" -o "$tmp/rs" --quiet --threads 1 >/dev/null 2>&1
check "the 200-step run exits 0" "$(yes01 test -f "$tmp/rs/checkpoint-000100.h5")"
listing "$tmp/rs" >"$tmp/before"
for end in "--until-step 30" "--until-time 0.0003" "--until-step 99"; do
    # shellcheck disable=SC2086
    "$bin" run "$tmp/s.yaml" --restart "$tmp/rs/checkpoint-000100.h5" -o "$tmp/rs" $end >"$tmp/past.out" \
        2>"$tmp/past.err"
    rc=$?
    listing "$tmp/rs" >"$tmp/after"
    check "restart from step 100 with $end: exit 2 (got $rc), one line, every file as it was" \
        "$([[ $rc == 2 && $(wc -l <"$tmp/past.err") == 1 ]] && grep -q "before the checkpoint's step 100" \
            "$tmp/past.err" && cmp -s "$tmp/before" "$tmp/after" && echo 1 || echo 0)"
done
cat "$tmp/past.err"
# the scene's own steps: are past too when the checkpoint is beyond them
sed 's/steps: 200/steps: 80/' "$tmp/s.yaml" >"$tmp/short.yaml"
"$bin" run "$tmp/short.yaml" --restart "$tmp/rs/checkpoint-000100.h5" -o "$tmp/rs" >/dev/null 2>"$tmp/short.err"
rc=$?
listing "$tmp/rs" >"$tmp/after"
check "a scene of 80 steps restarted from step 100 with no end given: exit 2 (got $rc), files as they were" \
    "$([[ $rc == 2 ]] && grep -q "the scene's steps: 80" "$tmp/short.err" && cmp -s "$tmp/before" "$tmp/after" &&
        echo 1 || echo 0)"
"$bin" run "$tmp/s.yaml" --steps 5 --until-step 9 -o "$tmp/two" >/dev/null 2>"$tmp/two.err"
rc=$?
check "--steps and --until-step together: exit 2 (got $rc), nothing made" \
    "$([[ $rc == 2 && ! -e $tmp/two ]] && grep -q "give one of" "$tmp/two.err" && echo 1 || echo 0)"

# ---- --steps N on a restart: N more steps, reported as such
"$bin" run "$tmp/s.yaml" --restart "$tmp/rs/checkpoint-000100.h5" -o "$tmp/more" --steps 30 >"$tmp/more.out" \
    2>&1
rc=$?
sum="$tmp/more/summary.txt"
check "--restart at 100 --steps 30: exit 0 (got $rc), ends at step 130, steps_run 30, start_step 100" \
    "$([[ $rc == 0 ]] && grep -q '^step: 130$' "$sum" && grep -q '^steps_run: 30$' "$sum" &&
        grep -q '^start_step: 100$' "$sum" && echo 1 || echo 0)"
check "and the summary line says 30 steps, restarted at step 100" \
    "$(yes01 grep -q 'particles, 30 steps .*restarted at step 100' <(tr '\n' ' ' <"$tmp/more.out"))"
"$bin" run "$tmp/s.yaml" --restart "$tmp/rs/checkpoint-000100.h5" -o "$tmp/until" --until-time 0.0015 --quiet
check "--until-time 0.0015 s at dt 1e-5 ends at step 150 (steps_run 50)" \
    "$([[ $? == 0 ]] && grep -q '^step: 150$' "$tmp/until/summary.txt" &&
        grep -q '^steps_run: 50$' "$tmp/until/summary.txt" && echo 1 || echo 0)"
"$bin" run "$tmp/s.yaml" --restart "$tmp/rs/checkpoint-000100.h5" -o "$tmp/abs" --until-step 200 --quiet
check "--until-step 200 continues to the reference's end: the same step-200 checkpoint" \
    "$([[ $? == 0 ]] && cmp -s <("$bin" info "$tmp/abs/checkpoint-000200.h5" | grep '^checksum') \
        <("$bin" info "$tmp/rs/checkpoint-000200.h5" | grep '^checksum') && echo 1 || echo 0)"
"$bin" run "$tmp/s.yaml" -o "$tmp/fresh" --until-step 40 --quiet
check "--until-step 40 on a fresh run: steps_run 40" "$(yes01 grep -q '^steps_run: 40$' "$tmp/fresh/summary.txt")"

# ---- SIGINT: acted on after the step in progress, and the whole command to continue
sed -e 's/steps: 200/steps: 100000000/' -e 's/output: .*/output: {every: 50000000, formats: [csv]}/' \
    "$tmp/s.yaml" >"$tmp/long.yaml"
mkdir -p "$tmp/it's here"
# interrupted ERR COMMAND: runs the (shell) command in "it's here" with its
# stderr in ERR, SIGINT once the run has used 1 s of CPU (it is stepping
# then; a fixed sleep could land in the start-up on a loaded machine, and a
# run stopped before its first step writes the checkpoint it started from);
# rc its exit status (timeout passes the signal on, and ends a run that
# would not stop)
interrupted() {
    (trap - EXIT; cd "$tmp/it's here" && eval "exec timeout -s KILL 60 $2" >/dev/null 2>"$1") &
    local pid=$! child="" ticks=0 i
    for ((i = 0; i < 300; ++i)); do
        sleep 0.1
        [[ -n $child ]] || child=$(pgrep -P $pid | head -1)
        [[ -n $child && -r /proc/$child/stat ]] || continue
        ticks=$(awk '{ print $14 }' "/proc/$child/stat" 2>/dev/null)
        (( ${ticks:-0} >= $(getconf CLK_TCK) )) && break
    done
    kill -INT $pid
    wait $pid
    rc=$?
}
interrupted "$tmp/int.err" "$(printf '%q ' "$bin") run ../long.yaml -o 'out dir' --threads 1 --quiet"
ck=$(ls "$tmp/it's here/out dir"/checkpoint-*.h5 2>/dev/null | tail -1)
step=${ck##*checkpoint-}
step=$((10#${step%.h5}))
check "SIGINT: exit 130 (got $rc) with a checkpoint at step $step, long before the first output at 50000000" \
    "$([[ $rc == 130 && -n $ck && $step -gt 0 && $step -lt 50000000 ]] && echo 1 || echo 0)"
again=$(sed -n 's/.*continue with: //p' "$tmp/int.err")
echo "  hint: $again"
check "the hint gives the scene, -o, --threads, --until-step 100000000 and the checkpoint" \
    "$([[ $again == *long.yaml* && $again == *"-o 'out dir'"* && $again == *"--threads 1"* &&
        $again == *"--until-step 100000000"* && $again == *checkpoint-*.h5* ]] && echo 1 || echo 0)"
# followed literally (from the same directory), it goes on in the same output directory
interrupted "$tmp/int2.err" "$again"
ck2=$(ls "$tmp/it's here/out dir"/checkpoint-*.h5 2>/dev/null | tail -1)
check "the hint, run as printed, continues in 'out dir' (exit $rc, checkpoint $(basename "$ck2") after $step)" \
    "$([[ $rc == 130 && $ck2 != "$ck" && ! -e "$tmp/it's here/out" ]] && echo 1 || echo 0)"
rows=$(grep -c '^[0-9]' "$tmp/it's here/out dir/stats.csv")
first=$(sed -n 2p "$tmp/it's here/out dir/stats.csv" | cut -d, -f1)
check "its stats.csv goes on from the first run's: the row of step 0 kept ($rows rows)" \
    "$([[ $first == 0 && $rows -ge 1 ]] && echo 1 || echo 0)"

# ---- --help everywhere
for c in run check info help shape "shape info" "shape fit-fourier" render; do
    # shellcheck disable=SC2086
    "$bin" $c --help >"$tmp/h.out" 2>"$tmp/h.err"
    rc=$?
    check "'$c --help': exit 0 (got $rc), its usage on stdout" \
        "$([[ $rc == 0 && ! -s $tmp/h.err ]] && grep -q "usage: shapedem ${c%% *}" "$tmp/h.out" && echo 1 || echo 0)"
done
"$bin" run --help | grep -q -- "--until-time" && "$bin" run --help | grep -q "N more steps"
check "run --help explains --steps on a restart and --until-step/--until-time" "$((! $?))"

# ---- --backend cuda blamed on the option or on the scene's backend: line
"$bin" check "$tmp/s.yaml" --backend cuda >/dev/null 2>"$tmp/cuda.err"
if grep -q "cannot run" "$tmp/cuda.err"; then
    check "--backend cuda on the command line: the message names the option ($(cat "$tmp/cuda.err"))" \
        "$(yes01 grep -q '^shapedem: --backend cuda: backend cuda cannot run' "$tmp/cuda.err")"
    sed 's/^simulation: {dt: 1.0e-5, steps: 200, seed: 3}/simulation:\n  dt: 1.0e-5\n  steps: 200\n  backend: cuda/' \
        "$tmp/s.yaml" >"$tmp/cuda.yaml"
    line=$(grep -n "backend: cuda" "$tmp/cuda.yaml" | cut -d: -f1)
    "$bin" check "$tmp/cuda.yaml" >/dev/null 2>"$tmp/cuda2.err"
    check "backend: cuda in the scene: the message points at its line $line ($(cat "$tmp/cuda2.err"))" \
        "$(yes01 grep -q "cuda.yaml:$line: simulation.backend: backend cuda cannot run" "$tmp/cuda2.err")"
else
    echo "  (this build runs CUDA: the refusal cannot be seen)"
fi

# ---- steps at the largest whole number: check reports it, without overflow
sed 's/steps: 200/steps: 9223372036854775807/' "$tmp/s.yaml" >"$tmp/huge.yaml"
"$bin" check "$tmp/huge.yaml" >"$tmp/huge.out" 2>&1
rc=$?
check "check of steps: 9223372036854775807: exit 0 or 1 (got $rc), a run time in years, not '--'" \
    "$([[ $rc == 0 || $rc == 1 ]] && grep -q "run time .*about [0-9.e+]* years" "$tmp/huge.out" &&
        ! grep -q "about --" "$tmp/huge.out" && echo 1 || echo 0)"
grep "run time" "$tmp/huge.out"

finish restart_steps
