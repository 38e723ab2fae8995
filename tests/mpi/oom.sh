#!/usr/bin/env bash
# oom.sh — a rank that runs out of memory mid-run ends the whole run with
# one clear message, never a hang (issue 18): tests/mpi/scene.c with
# --fail-alloc RANK:N makes the N-th allocation after attach fail on RANK
# only (core/alloc.h's hook); the N below land in different stages of a
# moving scene (see CASES). Each run must end under 60 s (124: a hang)
# with exit 1 (SD_ERR_MEMORY through sd_mpi_fail's MPI_Abort) and exactly
# one line of output besides mpirun's own: "shapedem: rank R of NP: ...",
# naming the rank and the stage and saying "out of memory".
# mpirun's own lines, filtered out (Open MPI 4 on MPI_Abort): the help
# block between two lines of dashes ("MPI_ABORT was invoked on rank R ...
# NOTE: invoking MPI_ABORT causes Open MPI to kill all MPI processes ..."),
# and its aggregation notes, "[host:pid] N more process(es) have sent help
# message ..." and "Set MCA parameter ... to see all help / error
# messages", and the "[host:pid] [[job,0],0] ORTE_ERROR_LOG: ... in file
# .../show_help.c" line mpirun itself (vpid 0 of job 0) sometimes prints
# when the aborting rank is killed while its help message is on the way. Anything else (another rank's message, a segfault's report, an
# MPI error from a half-sent exchange) fails the case.
#   oom.sh MPI_SCENE_BINARY MPIEXEC SOURCE_DIR
set -uo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
tmp=$(mktemp -d)
# Open MPI's session directory in this test's own $tmp (tests/mpi/lib.sh)
export OMPI_MCA_orte_tmpdir_base=$tmp
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
scene=$src/tests/mpi/scenes/walls.yaml
fail=0
# NP RANK N STAGE: the N-th allocation after attach fails on RANK (N:gather:
# from the final gather on); STAGE, what the message must name. The N were
# counted for this scene (a loop over N with mpi_scene shows the stage
# each one reaches): 1, the first step's table of material pairs; 2, the
# migration's own buffers; 5, a buffer after which the ranks vote (the
# others are told "another rank", and keep quiet: sd_mpi_fail); 7, the
# received rows (the others wait in the exchange until the abort); 30, the
# pair list of a later rebuild; gather 1 and 3, a rank's rows and rank 0's
# buffer for everyone's. Should the engine's allocations change, a case
# may land in another stage: the FAIL line shows which.
CASES=(
  "2 1 1 step failed .*material pairs"
  "2 1 2 step failed .*migration: out of memory (96 particles)"
  "2 1 5 step failed .*migration: out of memory on this rank"
  "2 1 7 step failed .*migration: out of memory for the received rows"
  "2 1 30 step failed .*building the pair list"
  "2 1 1:gather gather failed .*on this rank"
  "3 1 5 step failed .*migration: out of memory on this rank"
  "3 1 7 step failed .*migration: out of memory for the received rows"
  "3 1 30 step failed .*building the pair list"
  "3 1 1:gather gather failed .*on this rank"
  "2 0 5 step failed .*migration: out of memory on this rank"
  "3 0 3:gather gather failed .*on this rank for"
)
for c in "${CASES[@]}"; do
  read -r np r n stage <<<"$c"
  rc=0
  timeout 60 "$mpiexec" --oversubscribe --allow-run-as-root -np "$np" "$bin" "$scene" "$tmp/out.bin" \
    --fail-alloc "$r:$n" >"$tmp/log" 2>&1 || rc=$?
  # mpirun's own lines out (see above)
  awk '/^----------+$/ { inblock = !inblock; next } !inblock' "$tmp/log" |
    grep -v -e '^\[[^]]*\] [0-9]* more process' -e '^Set MCA parameter' \
      -e '^\[[^]]*\] \[\[[0-9]*,0\],0\] ORTE_ERROR_LOG: .*show_help\.c' >"$tmp/ours" || true
  lines=$(grep -c . "$tmp/ours" || true)
  if [[ $rc -eq 1 && $lines -eq 1 ]] &&
     grep -q "^shapedem: rank $r of $np: $stage" "$tmp/ours" && grep -q "out of memory" "$tmp/ours"; then
    echo "ok: $np ranks, allocation $n failing on rank $r: exit 1, one message: $(cat "$tmp/ours")"
  else
    echo "FAIL: $np ranks, allocation $n failing on rank $r: exit $rc (want 1; 124: a hang),"
    echo "  $lines lines besides mpirun's (want one naming rank $r of $np, '$stage', out of memory):"
    sed 's/^/  | /' "$tmp/log"
    fail=1
  fi
done
exit $fail
