#!/usr/bin/env bash
# stop_when.sh — simulation.stop_when ends a run when the particles are at
# rest (io/run.c):
#  - stop_scenes/settle.yaml (27 spheres settling, 1 s asked, stop below
#    1e-6 J after 0.05 s): the run exits 0 before its end; its last
#    stats.csv row is the first row at or after 0.05 s with kinetic energy
#    (translational + rotational) below 1e-6 J, every earlier row from
#    0.05 s on is at or above it; summary.txt's steps_run and stop_when line
#    name that step; a closing frame and the coordination row of that step
#    are written; stdout says so;
#  - with 1 thread it stops at the same row, the same energy to the digit;
#  - shapedem check on it prints the condition (its stop line);
#  - stop_scenes/never.yaml (a threshold of 1e-30 J): the run goes to its
#    end and summary.txt says the condition was not met;
#  - stop_scenes/settle-speed.yaml (mean_speed_below: 0.01 m/s): it stops
#    at the first row whose mean speed (energy.csv) is below it, the same
#    row on 1 and 2 threads.
# (Bad values of stop_when are scenes of tests/cli/bad/, stop-*.yaml.)
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=$root/tests/cli/stop_scenes

"$bin" run "$scenes/settle.yaml" --threads 2 -o "$tmp/s" >"$tmp/s.out" 2>"$tmp/s.err"
rc=$?
check "settle: exit 0 (got $rc)" "$((rc == 0))"
# the rows: step, time, kinetic energy; the first row from 0.05 s below 1e-6 J
read -r first last_step last_ke rows_above < <(awk -F, 'NR > 1 {
        ke = $3 + $4
        if ($2 >= 0.05 && ke < 1e-6 && first == "") first = $1
        if ($2 >= 0.05 && ke >= 1e-6) above++
        step = $1; last = ke
    } END { print (first == "" ? -1 : first), step, last, above + 0 }' "$tmp/s/stats.csv")
echo "     first row meeting it: step $first; last row: step $last_step, kinetic energy $last_ke J; rows from 0.05 s above: $rows_above"
check "settle: the run stopped at the first stats row meeting the condition (step $first, before 50000)" \
    "$([[ $first -gt 0 && $first -lt 50000 && $last_step == "$first" ]] && echo 1 || echo 0)"
check "settle: the rows before it from 0.05 s on were above the threshold ($rows_above of them)" \
    "$([[ $rows_above -ge 1 ]] && echo 1 || echo 0)"
grep "^stop_when: " "$tmp/s/summary.txt"
grep -q "^stop_when: met at step $first of 50000, t = " "$tmp/s/summary.txt"
check "settle: summary.txt's stop_when line says where it stopped" "$((! $?))"
grep -q "^steps_run: $first$" "$tmp/s/summary.txt"
check "settle: summary.txt's steps_run is $first" "$((! $?))"
t_stop=$(sed -n 's/^simulated_time_s: //p' "$tmp/s/summary.txt")
t_frame=$(grep -o 'timestep="[^"]*" group="" part="0"' "$tmp/s/frames.pvd" | tail -1 | cut -d'"' -f2)
echo "     stopped at t = $t_stop s; last frame at t = $t_frame s"
check "settle: the run closes with a frame where it stopped" \
    "$(awk -v a="$t_stop" -v b="$t_frame" 'BEGIN { d = a - b; print (a > 0 && d < 1e-12 && d > -1e-12) }')"
crow=$(awk -F, -v s="$first" 'NR > 1 && $2 == s { n++ } END { print n + 0 }' "$tmp/s/coordination.csv")
check "settle: coordination.csv has the row of step $first" "$((crow == 1))"
grep -q "stop_when met at step $first" "$tmp/s.out"
check "settle: stdout says the run stopped" "$((! $?))"

"$bin" run "$scenes/settle.yaml" --threads 1 --quiet -o "$tmp/s1" >/dev/null 2>&1
a=$(grep "^stop_when: " "$tmp/s/summary.txt")
b=$(grep "^stop_when: " "$tmp/s1/summary.txt")
check "settle: 1 thread stops at the same row with the same energy as 2" "$([[ -n $a && $a == "$b" ]] && echo 1 || echo 0)"

"$bin" check "$scenes/settle.yaml" --threads 1 >"$tmp/check.out"
grep "^stop " "$tmp/check.out"
grep -q "^stop         at the first stats row (every 250 steps) from t = 0.05 s whose kinetic energy is below 1e-06 J" \
    "$tmp/check.out"
check "check: says the run may stop early, when and below what" "$((! $?))"

"$bin" run "$scenes/never.yaml" --quiet -o "$tmp/n" >"$tmp/n.out" 2>"$tmp/n.err"
rc=$?
check "never: exit 0 (got $rc)" "$((rc == 0))"
grep "^stop_when: " "$tmp/n/summary.txt"
grep -q "^stop_when: not met (kinetic energy .* at step 5000, " "$tmp/n/summary.txt" &&
    grep -q "^steps_run: 5000$" "$tmp/n/summary.txt"
check "never: ran its 5000 steps, summary.txt says the condition was not met" "$((! $?))"

# the mean speed: the last stats row is the first energy.csv row from
# 0.05 s on whose mean_speed is below 0.01 m/s, and the same on 1 thread
"$bin" run "$scenes/settle-speed.yaml" --threads 2 --quiet -o "$tmp/v" >"$tmp/v.out" 2>&1
rc=$?
check "settle-speed: exit 0 (got $rc)" "$((rc == 0))"
read -r vfirst vabove < <(awk -F, 'NR > 1 && $1 >= 0.05 {
        if ($8 < 0.01 && first == "") first = $2
        if (first == "" && $8 >= 0.01) above++
    } END { print (first == "" ? -1 : first), above + 0 }' "$tmp/v/energy.csv")
vlast=$(tail -n 1 "$tmp/v/stats.csv" | cut -d, -f1)
grep "^stop_when: " "$tmp/v/summary.txt"
check "settle-speed: stopped at the first row with a mean speed below 0.01 m/s (step $vfirst, last stats row $vlast, $vabove rows above before it)" \
    "$([[ $vfirst -gt 0 && $vfirst -lt 50000 && $vlast == "$vfirst" && $vabove -ge 1 ]] && echo 1 || echo 0)"
grep -q "^stop_when: met at step $vfirst of 50000, t = .*: mean speed .* m/s below 0.01 m/s" "$tmp/v/summary.txt"
check "settle-speed: summary.txt names the mean speed" "$((! $?))"
"$bin" run "$scenes/settle-speed.yaml" --threads 1 --quiet -o "$tmp/v1" >/dev/null 2>&1
a=$(grep "^stop_when: " "$tmp/v/summary.txt")
b=$(grep "^stop_when: " "$tmp/v1/summary.txt")
check "settle-speed: 1 thread stops at the same row with the same mean speed as 2" "$([[ -n $a && $a == "$b" ]] && echo 1 || echo 0)"
"$bin" check "$scenes/settle-speed.yaml" --threads 1 | grep -q "^stop         at the first stats row (every 250 steps) from t = 0.05 s whose mean speed is below 0.01 m/s"
check "check: prints the mean-speed condition" "$((! $?))"

finish
