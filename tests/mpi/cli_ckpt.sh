#!/usr/bin/env bash
# cli_ckpt.sh — checkpoints written by every rank into one file through
# MPI-IO (issue 18; docs/mpi.md, src/mpi/ckpt.c): the file holds the same
# datasets, bit for bit, as the one rank 0 writes from the gathered view
# (SHAPEDEM_MPI_CHECKPOINT=rank0), in a box with walls, periodic along x
# and y, with composites, in a mesh drum and with an insertion and an
# outlet; a 2-rank checkpoint equals a 3-rank one; a checkpoint written in
# parallel on 2 or 3 ranks restarts on 1, 2 and 3 ranks to the bits of the
# uninterrupted run (its next checkpoint, every dataset), and in the serial
# program. shapedem links the serial HDF5, shapedem-mpi only the MPI one. A build without a parallel HDF5 writes from rank 0 both ways (CMake's
# SD_HDF5_MPIIO, the fifth argument, OFF): the test says so and checks the
# restarts alone.
#   cli_ckpt.sh SHAPEDEM MPIEXEC SOURCE_DIR CKPT_DIFF [MPIIO ON|OFF]
set -euo pipefail
bin=$1
mpiexec=${2:-mpirun}
src=$3
ckdiff=$4
mpiio=${5:-ON}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export OMP_NUM_THREADS=1
fail=0
source "$src/tests/mpi/lib.sh"

if [[ $mpiio != ON ]]; then
  echo "note: this build has no parallel HDF5: every file below is written by rank 0 (docs/mpi.md)"
fi
# one HDF5 per program: shapedem the serial one, shapedem-mpi (with
# MPI-IO) the MPI one only
needed() { readelf -d "$1" 2>/dev/null | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | tr '\n' ' '; }
serial=$(needed "$bin") par=$(needed "$(dirname "$bin")/shapedem-mpi")
if [[ $serial == *libhdf5_serial* && $serial != *hdf5_openmpi* ]] &&
  [[ $mpiio != ON || ($par == *libhdf5_openmpi* && $par != *libhdf5_serial*) ]]; then
  ok "shapedem needs $(grep -o 'libhdf5[^ ]*' <<<"$serial"); shapedem-mpi needs $(grep -o 'libhdf5[^ ]*' <<<"$par")"
else
  bad "the programs' HDF5 libraries: shapedem needs: $serial; shapedem-mpi needs: $par"
fi
same() { # name a.h5 b.h5: every dataset the same bits
  if "$ckdiff" "$2" "$3" >"$tmp/diff.out" 2>&1; then
    ok "$1: $(tail -n 1 "$tmp/diff.out")"
  else
    bad "$1:"
    cat "$tmp/diff.out"
  fi
}

sed 's/^  stats_every: 50$/  stats_every: 50\n  checkpoint_every: 200/' "$src/tests/mpi/run_scene.yaml" >"$tmp/box.yaml"
cp "$src/tests/mpi/run_periodic.yaml" "$tmp/periodic.yaml"
# every pair kind of composites (element pairs), a mesh wall's plane groups,
# an insertion of spheres and bricks with an outlet (mpi.kinds' scenes)
for mode in composites mesh process; do
  sed "s|file: .*/meshes/|file: $src/examples/meshes/|" "$src/tests/mpi/scenes/$mode.yaml" >"$tmp/$mode.yaml"
  printf 'output:\n  every: 100\n  stats_every: 50\n  checkpoint_every: 200\n  formats: [csv]\n' >>"$tmp/$mode.yaml"
done
for mode in box periodic composites mesh process; do
  scene=$tmp/$mode.yaml
  d=$tmp/$mode
  mpi -np 2 "$bin" run "$scene" --steps 200 -o "$d.p2" -q || bad "$mode: the 2-rank run failed"
  SHAPEDEM_MPI_CHECKPOINT=rank0 mpi -np 2 "$bin" run "$scene" --steps 200 -o "$d.r2" -q ||
    bad "$mode: the 2-rank run writing from rank 0 failed"
  ck=checkpoint-000200.h5
  same "$mode: written by 2 ranks through MPI-IO vs by rank 0 from the view" "$d.p2/$ck" "$d.r2/$ck"
  "$bin" info "$d.p2/$ck" >"$tmp/info.out" || bad "$mode: shapedem info refuses the parallel file"
  grep -q 'verified' "$tmp/info.out" && ok "$mode: shapedem info: $(grep '^particles' "$tmp/info.out")"
  [[ -z $(find "$d.p2" -name '*.tmp') ]] || bad "$mode: a temporary file was left in $d.p2"
done

# restarts: the box, written in parallel on 2 and on 3 ranks
scene=$tmp/box.yaml
d=$tmp/box
mpi -np 3 "$bin" run "$scene" --steps 200 -o "$d.p3" -q || bad "box: the 3-rank run failed"
same "box: written by 3 ranks vs by 2 ranks" "$d.p3/checkpoint-000200.h5" "$d.p2/checkpoint-000200.h5"
mpi -np 3 "$bin" run "$scene" -o "$d.whole" -q || bad "box: the uninterrupted 3-rank run failed"
for from in 2 3; do
  for np in 1 2 3; do
    [[ $from -eq 3 && $np -ne 2 ]] && continue # 3 -> 2 is enough for the second writer
    out=$d.rest$from$np
    mpi -np "$np" "$bin" run "$scene" --restart "$d.p$from/checkpoint-000200.h5" -o "$out" -q ||
      bad "box: the $np-rank restart of the $from-rank checkpoint failed"
    same "box: written on $from ranks at step 200, restarted on $np, at step 400 vs the uninterrupted run" \
      "$d.whole/checkpoint-000400.h5" "$out/checkpoint-000400.h5"
  done
done
# the serial program reads it as it reads rank 0's file (the same datasets,
# above; mpi.cli_restart compares its continuation with the MPI run's)
if "$bin" run "$scene" --restart "$d.p2/checkpoint-000200.h5" -o "$d.serial" -q &&
  grep -q 'step 400,' <<<"$("$bin" info "$d.serial/checkpoint-000400.h5")"; then
  ok "box: the serial program restarts from the 2-rank parallel checkpoint and reaches step 400"
else
  bad "box: the serial restart from the 2-rank parallel checkpoint failed"
fi
# a directory in the way of a checkpoint's temporary: since ad4bb25 the run
# refuses it before the first step (the serial check of the run's own
# names, which the .tmp clean-up made) instead of failing the collective
# write at step 200: one message, exit 2, no hang, nothing written over it.
# The collective write's own failure path (every rank takes the same way,
# 5b956ae) is no longer reached by this scene.
set +e
mpi -np 2 "$bin" run "$scene" --steps 50 -o "$tmp/way" -q
mkdir "$tmp/way/.checkpoint-000200.h5.tmp"
mpi -np 2 "$bin" run "$scene" --steps 200 -o "$tmp/way" -q 2>"$tmp/way.err"
rc=$?
set -e
if [[ $rc -eq 2 && ! -e $tmp/way/checkpoint-000200.h5 && -d $tmp/way/.checkpoint-000200.h5.tmp ]] &&
  [[ $(grep -c '^shapedem:' "$tmp/way.err") == 1 ]] &&
  grep -q '^shapedem: .*\.checkpoint-000200\.h5\.tmp: .*a directory' "$tmp/way.err"; then
  ok "a directory in the way of the temporary: exit 2 before the run, 1 message: $(grep '^shapedem:' "$tmp/way.err")"
else
  bad "a directory in the way of the temporary: exit $rc (124: a hang):"
  cat "$tmp/way.err"
fi
exit $fail
