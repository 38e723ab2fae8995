# lib.sh — what the mpirun CLI tests share (sourced by cli_ranks.sh and
# cli_restart.sh, which set $mpiexec and $fail).
ok() { echo "ok: $*"; }
bad() { echo "FAIL: $*"; fail=1; }
# mpirun oversubscribed (CI has two cores; as root Open MPI needs
# --allow-run-as-root), under a timeout: a hang fails with 124; Open MPI's
# session directory in the test's own $tmp, so that jobs started and ended
# at the same time by other tests (ctest -j) cannot remove it under this one
mpi() { OMPI_MCA_orte_tmpdir_base=$tmp timeout 300 "$mpiexec" --oversubscribe --allow-run-as-root "$@"; }
# a refused run: exit 2 and exactly one line from shapedem, matching pat
check_fail() { # name rc errfile pattern
  local n=$1 rc=$2 err=$3 pat=$4 msgs
  msgs=$(grep -c '^shapedem:' "$err" || true)
  if [[ $rc -eq 2 && $msgs -eq 1 ]] && grep -q "$pat" "$err"; then
    ok "$n: exit 2, one message: $(grep '^shapedem:' "$err")"
  else
    bad "$n: exit $rc (124: a hang), $msgs messages from shapedem:"
    cat "$err"
  fi
}
