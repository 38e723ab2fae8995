#!/usr/bin/env bash
# interrupt_placement.sh — the first SIGINT stops a long placement (issue
# 31): an insertion of 10^6 spheres at once, 10^5 attempts each, into a
# region that holds a few hundred places them all inside one step call,
# for minutes (the region jams and every later particle tries 10^5 spots
# until 1,000 in a row found none). Signals used to be seen only between
# step calls: the first SIGINT or SIGTERM was ignored until the placement
# ended (the probe's run kept going for 38 minutes). Now:
#  - SIGINT once the run has used 1 s of CPU (it is placing then): exit
#    130 within 10 s, "interrupted at step 0" and the command that
#    continues, a checkpoint at step 0 holding the particles placed so far,
#    every frame complete and no temporary left;
#  - the printed command continues the insertion from that checkpoint, and
#    SIGTERM stops it the same way, with more particles placed.
# The binary of ade592f keeps placing: killed after 60 s, exit 137.
set -u
bin="$1"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/jam.yaml" <<'EOF'
simulation: {dt: 1.0e-5, steps: 100, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.02, 0.02, 0.05], open: [zmax], material: g}]
insert:
  - {name: jam, region: box, min: [0.001, 0.001, 0.001], max: [0.019, 0.019, 0.019], count: 1000000,
     attempts: 100000, mix: [{material: g, radius: 0.001}]}
output: {every: 50}
EOF

# stopped SIG ERR COMMAND: runs the command in $tmp with stderr in ERR,
# sends SIG once it has used 1 s of CPU; rc its exit status, took the
# seconds from the signal to its end (a run that does not stop is killed
# 60 s after its start; on a loaded machine 1 s of CPU may take 20)
stopped() {
    (trap - EXIT; cd "$tmp" && eval "exec timeout -s KILL 60 $3" >/dev/null 2>"$2") &
    local pid=$! child="" ticks=0 i t0
    for ((i = 0; i < 450; ++i)); do
        sleep 0.1
        [[ -n $child ]] || child=$(pgrep -P $pid | head -1)
        [[ -n $child && -r /proc/$child/stat ]] || continue
        ticks=$(awk '{ print $14 }' "/proc/$child/stat" 2>/dev/null)
        (( ${ticks:-0} >= $(getconf CLK_TCK) )) && break
    done
    t0=$(date +%s.%N)
    kill -"$1" "${child:-$pid}"
    wait $pid
    rc=$?
    took=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
}
count() { "$bin" info "$1" 2>/dev/null | sed -n 's/^particles *\([0-9]*\).*/\1/p' | head -1; }

stopped INT "$tmp/int.err" "$(printf '%q ' "$bin") run jam.yaml -o out --quiet"
cat "$tmp/int.err"
ck="$tmp/out/checkpoint-000000.h5"
n0=$(count "$ck")
check "SIGINT during the placement: exit 130 (got $rc) in $took s (at most 10)" \
    "$([[ $rc == 130 ]] && awk -v t="$took" 'BEGIN { exit !(t <= 10) }' && echo 1 || echo 0)"
check "'interrupted at step 0' and the command that continues" \
    "$(grep -q "interrupted at step 0; .*continue with: .*--restart out/checkpoint-000000.h5" "$tmp/int.err" &&
        echo 1 || echo 0)"
check "the checkpoint at step 0 holds the particles placed so far ($n0)" \
    "$([[ -n $n0 && $n0 -gt 0 ]] && echo 1 || echo 0)"
ok=1
for f in "$tmp"/out/*.vtu "$tmp"/out/*.vtp; do
    [[ -e $f ]] || continue
    tail -c 20 "$f" | grep -q "</VTKFile>" || ok=0
done
check "every frame complete, no temporary left" \
    "$([[ $ok == 1 && -f $tmp/out/particles_000000.vtu && -z $(ls -A "$tmp/out" | grep -i tmp) ]] && echo 1 || echo 0)"

# the printed command goes on placing; SIGTERM stops it the same way
again=$(sed -n 's/.*continue with: //p' "$tmp/int.err")
if [[ -n $again ]]; then
    stopped TERM "$tmp/term.err" "$again"
    n1=$(count "$ck")
    check "the continued placement: SIGTERM, exit 130 (got $rc) in $took s, $n1 particles after $n0" \
        "$([[ $rc == 130 && -n $n1 && $n1 -gt $n0 ]] && awk -v t="$took" 'BEGIN { exit !(t <= 10) }' && echo 1 || echo 0)"
fi
finish
