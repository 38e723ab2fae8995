#!/usr/bin/env bash
# check_ranks.sh — `shapedem check --ranks N` (issue 18): the MPI split along
# x by particle count, in any build: N - 1 cuts, the particles per rank
# summing to the scene's and differing by at most one; a bad N is refused
# (exit 2, one line naming the option).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
scene="$root/examples/settle-spheres.yaml"
out=$("$bin" check "$scene" --ranks 3 2>&1)
rc=$?
line=$(grep '^ranks ' <<<"$out")
echo "$line"
total=$(grep '^particles ' <<<"$out" | sed -E 's/^particles +([0-9]+).*/\1/')
counts=$(sed -E 's/.*particles per rank //' <<<"$line")
cuts=$(sed -E 's/.*cuts at x = ([^m]*) m;.*/\1/' <<<"$line" | tr ',' '\n' | grep -c .)
sum=0 lo=-1 hi=-1
for c in $counts; do
    sum=$((sum + c))
    ((lo < 0 || c < lo)) && lo=$c
    ((c > hi)) && hi=$c
done
echo "particles $total; per rank: $counts (sum $sum, spread $((hi - lo))); $cuts cuts"
check "check --ranks 3 runs (rc $rc)" "$((rc == 0))"
check "3 ranks: 2 cuts, every particle on one rank ($sum of $total), counts within 1" \
    "$([[ $cuts == 2 && $sum == "$total" && $((hi - lo)) -le 1 ]] && echo 1 || echo 0)"
err=$("$bin" check "$scene" --ranks 0 2>&1 >/dev/null)
rc=$?
echo "$err"
check "--ranks 0 is refused with exit 2 naming --ranks" \
    "$([[ $rc == 2 && $(grep -c -- '--ranks' <<<"$err") == 1 ]] && echo 1 || echo 0)"
finish
