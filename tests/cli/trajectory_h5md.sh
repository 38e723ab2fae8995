#!/usr/bin/env bash
# trajectory_h5md.sh — output.formats: [h5md] writes trajectory.h5md, the
# particles of every frame in the layout of H5MD 1.1 (docs/output.md):
# - for plain spheres, composites (periodic in y), the planar mode
#   (dimension 2) and spheres inserted during the run (tests/cli/reader_scenes/;
#   cli.trajectory_dump covers the shapes and the mesh drum, which go
#   through the same particle reader), tests/tools/h5md_check.py reads it with
#   h5py, finds the standard's required groups and attributes, and every
#   frame equal to its particle frame (ids, positions, velocities, radii;
#   rows past a frame's count filled with id -1 and NaN);
# - the same bytes with 1 and 2 threads;
# - a restart from the checkpoint at step 10 into the run's directory
#   holds the uninterrupted run's values; one over a file HDF5 cannot open
#   (a crash) or into a new directory starts a new file at the restart step;
# - the same values on 1 and 2 MPI ranks (where the build has shapedem-mpi);
# - formats: [h5md] alone writes it without VTK frames;
# - a misspelt format is refused with the scene's file, line and key and
#   exit status 2.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
py=/usr/bin/python3  # Debian's interpreter, the one python3-h5py installs into
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes="$root/tests/cli/reader_scenes"
same() { "$py" "$root/tests/tools/h5md_check.py" --same "$1" "$2"; }
steps() { "$py" -c 'import h5py, sys; print(*h5py.File(sys.argv[1], "r")["particles/all/position/step"][()])' "$1" 2>&1; }
# scene, time step, periodic axes
for spec in spheres:1.0e-5: composites:1.0e-5:y planar:1.0e-5: insert:1.0e-5:; do
    IFS=: read -r s dt per <<<"$spec"
    sed -e 's/formats: \[[a-z0-9, ]*\]/formats: [vtk, h5md]/' "$scenes/$s.yaml" >"$tmp/$s.yaml"
    "$bin" run "$tmp/$s.yaml" --threads 2 --quiet -o "$tmp/$s" >"$tmp/$s.log" 2>&1
    rc=$?
    check "$s runs with formats [vtk, h5md] (rc $rc)" "$((rc == 0))" "$(tail -3 "$tmp/$s.log")"
    "$py" "$root/tests/tools/h5md_check.py" "$root" "$tmp/$s" "$dt" "$per"
    check "$s: trajectory.h5md is H5MD and holds the frames" "$(($? == 0))"
done

"$bin" run "$tmp/insert.yaml" --threads 1 --quiet -o "$tmp/one" >"$tmp/one.log" 2>&1
check "insert: the same trajectory.h5md bytes with 1 and 2 threads" \
    "$(yes01 cmp -s "$tmp/one/trajectory.h5md" "$tmp/insert/trajectory.h5md")"

# restarts: b stops at step 10 (its checkpoint), then goes on
sed 's/checkpoint_every: 20/checkpoint_every: 10/' "$tmp/insert.yaml" >"$tmp/ck.yaml"
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/a" >"$tmp/a.log" 2>&1
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/b" --steps 10 >"$tmp/b1.log" 2>&1
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/b" --restart "$tmp/b/checkpoint-000010.h5" >"$tmp/b2.log" 2>&1
rc=$?
same "$tmp/a/trajectory.h5md" "$tmp/b/trajectory.h5md"
check "a restart continues trajectory.h5md: the uninterrupted run's values (rc $rc; steps $(steps "$tmp/b/trajectory.h5md"))" \
    "$(($? == 0 && rc == 0))"
# c: the full run's directory with a file HDF5 cannot open
mkdir -p "$tmp/c" && cp -a "$tmp/a/." "$tmp/c/"
head -c 3000 "$tmp/a/trajectory.h5md" >"$tmp/c/trajectory.h5md"
"$bin" run "$tmp/ck.yaml" --threads 1 --quiet -o "$tmp/c" --restart "$tmp/c/checkpoint-000020.h5" >"$tmp/c.log" 2>&1
rc=$?
got=$(steps "$tmp/c/trajectory.h5md")
check "a restart over a damaged trajectory.h5md starts a new one at the restart step (rc $rc; steps $got)" \
    "$([[ $rc == 0 && $got == "20 30 40" ]] && echo 1 || echo 0)"
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/d" --restart "$tmp/a/checkpoint-000010.h5" >"$tmp/d.log" 2>&1
got=$(steps "$tmp/d/trajectory.h5md")
check "a restart into a new directory starts trajectory.h5md at the restart step (steps $got)" \
    "$([[ $got == "10 20 30 40" ]] && echo 1 || echo 0)"

# a decomposed run (docs/mpi.md): rank 0 gathers the particles and writes
# the same values as one rank; where the build has shapedem-mpi
if command -v mpirun >/dev/null && [[ -x "$(dirname "$bin")/shapedem-mpi" ]]; then
    for np in 1 2; do
        OMP_NUM_THREADS=1 OMPI_MCA_orte_tmpdir_base="$tmp" timeout 300 mpirun --oversubscribe --allow-run-as-root \
            -np $np "$bin" run "$tmp/spheres.yaml" --quiet -o "$tmp/np$np" >"$tmp/np$np.log" 2>&1
    done
    split=$(sed -n 's/^mpi_particles_per_rank: //p' "$tmp/np2/summary.txt" 2>/dev/null)
    same "$tmp/np1/trajectory.h5md" "$tmp/np2/trajectory.h5md"
    check "spheres on 2 ranks (particles per rank: $split): the same trajectory.h5md values as on 1 rank" \
        "$(($? == 0))"
else
    echo "SKIP the 2-rank run: no mpirun or no shapedem-mpi beside $bin"
fi

sed 's/formats: \[vtk, h5md\]/formats: [h5md]/' "$tmp/spheres.yaml" >"$tmp/only.yaml"
"$bin" run "$tmp/only.yaml" --quiet -o "$tmp/only" >"$tmp/only.log" 2>&1
rc=$?
got=$(steps "$tmp/only/trajectory.h5md")
check "formats [h5md] alone: frames at steps $got, no VTK frames (rc $rc)" \
    "$([[ $rc == 0 && $got == "0 10 20" && ! -e $tmp/only/frames.pvd ]] && echo 1 || echo 0)"

sed 's/formats: \[vtk, h5md\]/formats: [vtk, hdf5]/' "$tmp/spheres.yaml" >"$tmp/bad.yaml"
"$bin" run "$tmp/bad.yaml" --quiet -o "$tmp/bad" >"$tmp/bad.log" 2>&1
rc=$?
line=$(grep -n 'formats:' "$tmp/bad.yaml" | cut -d: -f1)
msg=$(head -1 "$tmp/bad.log")
check "a misspelt format: exit 2, one message with file, line and key, nothing written ($msg)" \
    "$([[ $rc == 2 && $msg == *bad.yaml:$line* && $msg == *formats* && $msg == *h5md* && ! -e $tmp/bad ]] && echo 1 || echo 0)"
finish
