#!/usr/bin/env bash
# vtk_readers.sh — a run's files open in VTK's own XML readers (python3-vtk9,
# the library ParaView is built on; scripts/deps.sh), for every kind of
# scene: plain spheres with a box and a plane, the convex shapes and a
# polyhedron in a drum, composites with a periodic axis, a turning mesh
# drum, the planar mode and spheres inserted during the run
# (tests/cli/reader_scenes/, 20 or 40 steps each, frames with true shapes
# but the last). tests/tools/vtk_readers.py opens frames.pvd and
# every file it lists, fails on any message VTK gives, and checks counts,
# arrays and the last frame against the run's checkpoint bit for bit.
# Skipped (exit 77, ctest's SKIP_RETURN_CODE) where vtk does not import.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
py=/usr/bin/python3  # Debian's interpreter, the one python3-vtk9 installs into
if ! "$py" -c 'import vtkmodules.vtkIOXML' 2>/dev/null; then
    echo "SKIP: $py cannot import vtk (scripts/deps.sh installs python3-vtk9)"
    exit 77
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes="$root/tests/cli/reader_scenes"
args=()
for s in spheres shapes composites mesh planar insert; do
    "$bin" run "$scenes/$s.yaml" --threads 2 --quiet -o "$tmp/$s" >"$tmp/$s.log" 2>&1
    rc=$?
    check "$s.yaml runs (rc $rc)" "$((rc == 0))" "$(tail -3 "$tmp/$s.log")"
    args+=("$tmp/$s")
done
# composites.yaml is periodic in y with a period of 0.024 m
args[2]="${args[2]}:0.024"
TMPDIR="$tmp" "$py" "$root/tests/tools/vtk_readers.py" "${args[@]}"
check "VTK's readers open every file and the data are the run's" "$(($? == 0))"
finish
