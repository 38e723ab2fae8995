#!/usr/bin/env bash
# example_meshes.sh — the committed meshes of the mesh-wall examples
# (examples/meshes/*.obj) are exactly what scripts/make_meshes.py writes,
# so the script stays the source of every mesh file, and each reads and is
# prepared by `shapedem check` of its example scene (exit 0, no repairs).
#
# Usage: bash example_meshes.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: example_meshes.sh SHAPEDEM REPO}
repo=${2:?usage: example_meshes.sh SHAPEDEM REPO}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_example_meshes.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
pass=0
fail=0
report() { # report 1|0 name detail
    if [[ $1 == 1 ]]; then pass=$((pass + 1)); echo "PASS $2: $3"; else fail=$((fail + 1)); echo "FAIL $2: $3"; fi
}
/usr/bin/python3 "$repo/scripts/make_meshes.py" examples "$tmp" >/dev/null
for f in "$tmp"/*.obj; do
    name=$(basename "$f")
    same=$(cmp -s "$f" "$repo/examples/meshes/$name" && echo 1 || echo 0)
    report "$same" "examples/meshes/$name" "the output of scripts/make_meshes.py examples ($(wc -c <"$f") bytes)"
done
for scene in "$repo"/examples/mesh-*.yaml; do
    out=$("$exe" check "$scene" --threads 1 2>&1)
    rc=$?
    ok=$([[ $rc == 0 && $out != *"warning      wall"* ]] && echo 1 || echo 0)
    report "$ok" "check $(basename "$scene")" "exit $rc, $(printf '%s\n' "$out" | grep -c 'warning      wall') wall warnings"
done
echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
