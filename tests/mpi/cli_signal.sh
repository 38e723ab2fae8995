#!/usr/bin/env bash
# cli_signal.sh — a signal sent to one rank other than 0 stops the whole
# mpirun job cleanly (issue 31, probe 3): rank 0 writes the final
# checkpoint, prints the command that continues the run (mpirun -np 2 and
# the whole command line) and the job exits 130. Before, ranks other than 0
# ignored SIGINT and SIGTERM: the job ran on.
#   cli_signal.sh SHAPEDEM MPIEXEC
set -u
bin=$1
mpiexec=${2:-mpirun}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
cat >"$tmp/long.yaml" <<'YAML'
simulation: {dt: 1.0e-5, steps: 100000000, seed: 3}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: lattice, material: g, radius: 0.001, origin: [0.002, 0.002, 0.002], spacing: 0.003, count: [3, 3, 3]}]
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.02, 0.02, 0.05], open: [zmax], material: g}]
output: {every: 50000000, formats: [csv]}
YAML
for sig in TERM INT; do
  d=$tmp/o$sig
  # the run would take days: only the signal ends it (the timeout: a failure)
  (trap - EXIT; OMPI_MCA_orte_tmpdir_base=$tmp exec timeout -s KILL 120 "$mpiexec" --oversubscribe \
    --allow-run-as-root -np 2 "$bin" run "$tmp/long.yaml" -o "$d" --quiet >/dev/null 2>"$d.err") &
  job=$!
  rank1=""
  for _ in $(seq 1 100); do # rank 1's process, by its environment
    for p in $(pgrep -f "shapedem-mpi run $tmp/long.yaml" 2>/dev/null); do
      [[ $p != "$job" ]] && tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=1" &&
        rank1=$p
    done
    [[ -n $rank1 && -f $d/stats.csv ]] && break
    sleep 0.2
  done
  sleep 1
  [[ -n $rank1 ]] && kill -"$sig" "$rank1"
  wait $job
  rc=$?
  ck=$(ls "$d"/checkpoint-*.h5 2>/dev/null | tail -n 1)
  if [[ -n $rank1 && $rc == 130 && -n $ck ]] && grep -q "continue with: mpirun -np 2 .* --restart $ck" "$d.err"; then
    ok "SIG$sig to rank 1 (pid $rank1): exit 130, final checkpoint $(basename "$ck"), the command to continue"
  else
    bad "SIG$sig to rank 1 (pid ${rank1:-not found}): exit $rc (137: the job ran on), checkpoint '${ck}'"
    cat "$d.err"
  fi
done
exit $fail
