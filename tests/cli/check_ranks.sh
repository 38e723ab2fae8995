#!/usr/bin/env bash
# check_ranks.sh — `shapedem check --ranks N` (issue 18): the MPI split
# (the grid of boxes by particle count, docs/mpi.md), in any build: the
# grid's line, one line per rank with its box and particles, the counts
# summing to the scene's and differing by at most one; a bad N is refused
# (exit 2, one line naming the option).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
scene="$root/examples/settle-spheres.yaml"
total=$("$bin" check "$scene" 2>&1 | grep '^particles ' | sed -E 's/^particles +([0-9]+).*/\1/')
for r in 3 4; do
    out=$("$bin" check "$scene" --ranks $r 2>&1)
    rc=$?
    grep -A$r '^ranks ' <<<"$out"
    grid=$(sed -nE 's/^ranks +[0-9]+: ([0-9]+) x ([0-9]+) x ([0-9]+) boxes.*/\1 \2 \3/p' <<<"$out")
    counts=$(sed -nE 's/^  rank +[0-9]+ +\[.*\] m: ([0-9]+) particles$/\1/p' <<<"$out")
    sum=0 lo=-1 hi=-1 n=0
    for c in $counts; do
        sum=$((sum + c)) n=$((n + 1))
        ((lo < 0 || c < lo)) && lo=$c
        ((c > hi)) && hi=$c
    done
    read -r px py pz <<<"${grid:-0 0 0}"
    echo "particles $total; grid $px x $py x $pz; per rank: $(echo $counts) (sum $sum, spread $((hi - lo)))"
    check "check --ranks $r runs (rc $rc)" "$((rc == 0))"
    check "$r ranks: a grid of $r boxes, $r box lines, every particle on one rank ($sum of $total), counts within 1" \
        "$([[ $((px * py * pz)) == "$r" && $n == "$r" && $sum == "$total" && $((hi - lo)) -le 1 ]] && echo 1 || echo 0)"
done
err=$("$bin" check "$scene" --ranks 0 2>&1 >/dev/null)
rc=$?
echo "$err"
check "--ranks 0 is refused with exit 2 naming --ranks" \
    "$([[ $rc == 2 && $(grep -c -- '--ranks' <<<"$err") == 1 ]] && echo 1 || echo 0)"
finish
