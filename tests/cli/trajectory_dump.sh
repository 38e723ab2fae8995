#!/usr/bin/env bash
# trajectory_dump.sh — output.formats: [dump] writes trajectory.dump, LAMMPS
# dump text (docs/output.md), one snapshot per frame:
# - for plain spheres, convex shapes, composites (periodic in y: bounds
#   "pp" there), a mesh drum, the planar mode and spheres inserted during
#   the run (tests/cli/reader_scenes/),
#   tests/tools/dump_check.py parses it and finds every snapshot equal to
#   its particle frame (positions, velocities, spins, radii, orientations);
# - the same bytes with 1 and 2 threads;
# - a restart from the checkpoint at step 10 into the run's directory gives
#   the uninterrupted run's file byte for byte, also when the file was cut
#   inside its last snapshot (a crash) or holds snapshots past the restart;
#   a restart into a new directory starts a new file at the restart step;
# - the same bytes on 1 and 2 MPI ranks (where the build has shapedem-mpi);
# - formats: [dump] alone writes the snapshots without frames;
# - a misspelt format is refused with the scene's file, line and key and
#   exit status 2, and nothing is written.
set -u
bin="$1"
root=$(cd "$2" && pwd)  # absolute: the mesh file is named from it
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
py=/usr/bin/python3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes="$root/tests/cli/reader_scenes"
# scene, time step, periodic axes
for spec in spheres:1.0e-5: shapes:2.0e-6: composites:1.0e-5:y mesh:7.0e-6: planar:1.0e-5: insert:1.0e-5:; do
    IFS=: read -r s dt per <<<"$spec"
    # frames and the dump only; the mesh file (relative to the scene) named from the root
    sed -e 's/formats: \[[a-z0-9, ]*\]/formats: [vtk, dump]/' \
        -e "s#file: \.\./\.\./\.\./#file: $root/#" "$scenes/$s.yaml" >"$tmp/$s.yaml"
    "$bin" run "$tmp/$s.yaml" --threads 2 --quiet -o "$tmp/$s" >"$tmp/$s.log" 2>&1
    rc=$?
    check "$s runs with formats [vtk, dump] (rc $rc)" "$((rc == 0))" "$(tail -3 "$tmp/$s.log")"
    "$py" "$root/tests/tools/dump_check.py" "$root" "$tmp/$s" "$dt" "$per"
    check "$s: trajectory.dump holds the frames" "$(($? == 0))"
done

"$bin" run "$tmp/shapes.yaml" --threads 1 --quiet -o "$tmp/one" >"$tmp/one.log" 2>&1
check "shapes: the same trajectory.dump with 1 and 2 threads" "$(yes01 cmp -s "$tmp/one/trajectory.dump" "$tmp/shapes/trajectory.dump")"

# restarts: b stops at step 10 (its checkpoint), then goes on
sed 's/checkpoint_every: 20/checkpoint_every: 10/' "$tmp/shapes.yaml" >"$tmp/ck.yaml"
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/a" >"$tmp/a.log" 2>&1
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/b" --steps 10 >"$tmp/b1.log" 2>&1
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/b" --restart "$tmp/b/checkpoint-000010.h5" >"$tmp/b2.log" 2>&1
rc=$?
check "a restart continues trajectory.dump: the uninterrupted run's bytes (rc $rc)" \
    "$([[ $rc == 0 ]] && cmp -s "$tmp/a/trajectory.dump" "$tmp/b/trajectory.dump" && echo 1 || echo 0)"
# c: a full run whose file is then cut inside its last snapshot
mkdir -p "$tmp/c" && cp -a "$tmp/a/." "$tmp/c/"
size=$(stat -c %s "$tmp/c/trajectory.dump")
truncate -s $((size - 40)) "$tmp/c/trajectory.dump"
"$bin" run "$tmp/ck.yaml" --threads 1 --quiet -o "$tmp/c" --restart "$tmp/c/checkpoint-000010.h5" >"$tmp/c.log" 2>&1
rc=$?
check "a restart over a file cut inside a snapshot and holding ones past the restart: the same bytes (rc $rc)" \
    "$([[ $rc == 0 ]] && cmp -s "$tmp/a/trajectory.dump" "$tmp/c/trajectory.dump" && echo 1 || echo 0)"
"$bin" run "$tmp/ck.yaml" --threads 2 --quiet -o "$tmp/d" --restart "$tmp/a/checkpoint-000010.h5" >"$tmp/d.log" 2>&1
steps=$(grep -A1 '^ITEM: TIMESTEP' "$tmp/d/trajectory.dump" 2>/dev/null | grep -v '^ITEM\|^--' | tr '\n' ' ')
check "a restart into a new directory starts trajectory.dump at the restart step (steps: $steps)" \
    "$([[ $steps == "10 20 " ]] && echo 1 || echo 0)"

# a decomposed run (docs/mpi.md): rank 0 gathers the particles and writes
# the same file as one rank; where the build has shapedem-mpi
if command -v mpirun >/dev/null && [[ -x "$(dirname "$bin")/shapedem-mpi" ]]; then
    for np in 1 2; do
        OMP_NUM_THREADS=1 OMPI_MCA_orte_tmpdir_base="$tmp" timeout 300 mpirun --oversubscribe --allow-run-as-root \
            -np $np "$bin" run "$tmp/mesh.yaml" --quiet -o "$tmp/np$np" >"$tmp/np$np.log" 2>&1
    done
    split=$(sed -n 's/^mpi_particles_per_rank: //p' "$tmp/np2/summary.txt" 2>/dev/null)
    check "mesh on 2 ranks (particles per rank: $split): the same trajectory.dump as on 1 rank" \
        "$([[ $split == *" "* ]] && cmp -s "$tmp/np1/trajectory.dump" "$tmp/np2/trajectory.dump" && echo 1 || echo 0)"
else
    echo "SKIP the 2-rank run: no mpirun or no shapedem-mpi beside $bin"
fi

sed 's/formats: \[vtk, dump\]/formats: [dump]/' "$tmp/spheres.yaml" >"$tmp/only.yaml"
"$bin" run "$tmp/only.yaml" --quiet -o "$tmp/only" >"$tmp/only.log" 2>&1
rc=$?
n=$(grep -c '^ITEM: TIMESTEP' "$tmp/only/trajectory.dump" 2>/dev/null)
check "formats [dump] alone: $n snapshots, no frames (rc $rc)" \
    "$([[ $rc == 0 && $n == 3 && ! -e $tmp/only/frames.pvd ]] && echo 1 || echo 0)"
cmp -s <(sed -n '/^ITEM: ATOMS/,$p' "$tmp/only/trajectory.dump") <(sed -n '/^ITEM: ATOMS/,$p' "$tmp/spheres/trajectory.dump")
check "formats [dump] alone: the same snapshots as with the frames" "$(($? == 0))"

sed 's/formats: \[vtk, dump\]/formats: [vtk, lammps]/' "$tmp/spheres.yaml" >"$tmp/bad.yaml"
"$bin" run "$tmp/bad.yaml" --quiet -o "$tmp/bad" >"$tmp/bad.log" 2>&1
rc=$?
line=$(grep -n 'formats:' "$tmp/bad.yaml" | cut -d: -f1)
msg=$(head -1 "$tmp/bad.log")
check "a misspelt format: exit 2, one message with file, line and key, nothing written ($msg)" \
    "$([[ $rc == 2 && $msg == *bad.yaml:$line* && $msg == *formats* && $msg == *dump* && ! -e $tmp/bad ]] && echo 1 || echo 0)"
finish
