#!/usr/bin/env bash
# memcheck.sh BIN ROOT SCENE STEPS — a short run of SCENE under valgrind's
# memcheck (ctest memcheck.run_short): no memory definitely or indirectly
# lost and no invalid read or write, with output written (frames,
# stats.csv, summary.txt) and 2 OpenMP threads. Exit 77 (ctest: skipped)
# when valgrind is not installed; scripts/deps.sh installs it.
#
# "Possibly lost" and "still reachable" blocks are not counted: libgomp
# keeps its thread pool until exit, which valgrind reports as such, and
# that is not a leak of ours.
set -u
bin=$1 root=$2 scene=$3 steps=$4
if ! command -v valgrind >/dev/null 2>&1; then
  echo "SKIP valgrind is not installed (scripts/deps.sh installs it)"
  exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
log=$tmp/memcheck.log
OMP_NUM_THREADS=2 valgrind --tool=memcheck --leak-check=full --errors-for-leak-kinds=definite,indirect \
  --show-leak-kinds=definite,indirect --error-exitcode=99 --log-file="$log" \
  "$bin" run "$root/$scene" --steps "$steps" -o "$tmp/out" >"$tmp/run.out" 2>&1
rc=$?
grep -E "definitely lost|indirectly lost|ERROR SUMMARY" "$log"
definite=$(sed -n 's/.*definitely lost: \([0-9,]*\) bytes.*/\1/p' "$log" | tr -d ,)
indirect=$(sed -n 's/.*indirectly lost: \([0-9,]*\) bytes.*/\1/p' "$log" | tr -d ,)
errors=$(sed -n 's/.*ERROR SUMMARY: \([0-9,]*\) errors.*/\1/p' "$log" | tr -d ,)
# no "definitely lost" line at all means valgrind found no leaked block
definite=${definite:-0} indirect=${indirect:-0}
echo "run of $scene, $steps steps: exit $rc, definitely lost $definite bytes, indirectly lost $indirect bytes," \
  "memcheck errors ${errors:-?} (expected 0, 0, 0)"
if [[ $rc -ne 0 || $definite != 0 || $indirect != 0 || ${errors:-x} != 0 ]]; then
  echo "FAIL memcheck: the run or valgrind reported a problem; valgrind's log:"
  cat "$log"
  echo "the run's output:"
  cat "$tmp/run.out"
  exit 1
fi
if [[ ! -s $tmp/out/summary.txt ]]; then
  echo "FAIL the run wrote no summary.txt (did it run?)"
  cat "$tmp/run.out"
  exit 1
fi
echo "PASS no leak and no memory error under valgrind"
