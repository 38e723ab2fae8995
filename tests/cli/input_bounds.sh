#!/usr/bin/env bash
# input_bounds.sh — text tables and mesh files that used to be read wrong
# without a word, and `check`'s mesh and analysis-size lines (issue 31,
# probe 3 findings 13, 14 and the low ones; issue 30's mesh report):
#  - a motion table's first row that looks numeric but does not parse
#    (a comment after it, a hex number, empty fields) is refused with its
#    line, not dropped as a header; a named header is still taken;
#  - a UTF-8 byte-order mark is skipped (motion table, particle CSV); a NUL
#    byte and a directory are called that;
#  - an ASCII STL cut inside a facet is refused, at every cut;
#  - a mesh 30,000 particle diameters wide (left in millimetres) gets a
#    line with its facets, box and size and a warning to check scale:,
#    and loads at once (its facet bins are bounded); scale: 1e-300 and a
#    vertex at 1e99 are called wrong units;
#  - check estimates the analysis files' size and warns when large, and
#    warns of insertion regions across or outside the walls.
#
# Usage: bash input_bounds.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: input_bounds.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
source "$(dirname "$0")/lib.sh"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_input_bounds.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
report() { check "$2: $3" "$1"; } # report 1|0 NAME DETAIL

# refused NAME TEXT...: `check NAME.yaml` exits 2 with one stderr line
# holding each TEXT.
refused() {
    local name=$1 err rc n ok=1
    shift
    err=$("$exe" check "$name.yaml" 2>&1 >/dev/null)
    rc=$?
    n=$(printf '%s\n' "$err" | wc -l)
    [[ $rc == 2 && $n == 1 ]] || ok=0
    for text in "$@"; do [[ $err == *"$text"* ]] || ok=0; done
    report $ok "$name" "exit $rc, $n line(s): $err"
}
# accepted NAME: `check NAME.yaml` exits 0.
accepted() {
    local out rc
    out=$("$exe" check "$1.yaml" 2>&1)
    rc=$?
    report "$([[ $rc == 0 ]] && echo 1 || echo 0)" "$1" "exit $rc${2:+: $2}"
    [[ $rc == 0 ]] || printf '%s\n' "$out" | tail -3
}

# A 2-facet ASCII floor of half-width L (mesh units).
floor() { # floor FILE L
    python3 - "$1" "$2" <<'EOF'
import sys
L = float(sys.argv[2])
s = "solid floor\n"
for tri in [((-L, -L, 0), (L, -L, 0), (L, L, 0)), ((-L, -L, 0), (L, L, 0), (-L, L, 0))]:
    s += " facet normal 0 0 1\n  outer loop\n"
    for v in tri:
        s += "   vertex %r %r %r\n" % v
    s += "  endloop\n endfacet\n"
s += "endsolid floor\n"
open(sys.argv[1], "w").write(s)
EOF
}
# mesh_scene NAME WALL-KEYS: one sphere of 1 mm over a mesh wall.
mesh_scene() {
    cat >"$1.yaml" <<EOF
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0.002], radius: 0.001}]}]
walls: [{type: mesh, name: w, material: m, $2}]
EOF
}

# --- motion tables ---------------------------------------------------------
floor floor.stl 0.01
table_scene() { mesh_scene "$1" "file: floor.stl, motion: {type: table, table: $1.csv}"; }
printf '0,0,0,0,0 # start at rest\n0.01,0.005,0,0,0\n' >comment.csv
table_scene comment
refused comment "comment.csv line 1" "expected 5 finite decimal numbers" "walls[0].motion.table"
printf '0x0,0,0,0,0\n0.01,0.005,0,0,0\n' >hex.csv
table_scene hex
refused hex "hex.csv line 1"
printf '0,,,,\n0.01,0.005,0,0,0\n' >empty.csv
table_scene empty
refused empty "empty.csv line 1"
printf 't,dx,dy,dz,angle_deg\n0,0,0,0,0\n0.01,0.005,0,0,0\n' >named.csv
table_scene named
accepted named "a named header is taken"
# a BOM before the first row: the row is read (here its repeated t is refused at line 2)
printf '\xef\xbb\xbf0,0,0,0,0\n0,0.005,0,0,0\n' >bom.csv
table_scene bom
refused bom "bom.csv line 2" "does not increase"
printf '\xef\xbb\xbft,dx,dy,dz,angle_deg\n0,0,0,0,0\n0.01,0.005,0,0,0\n' >bomhead.csv
table_scene bomhead
accepted bomhead "a header after a BOM"
printf '0,0,0\x000,0\n' >nul.csv
table_scene nul
refused nul "nul.csv line 1" "NUL byte"
mkdir dir.csv
table_scene dir
refused dir "dir.csv' is a directory"

# --- particle CSV ------------------------------------------------------------
csv_scene() {
    cat >"$1.yaml" <<EOF
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: csv, file: $1.csv, material: m}]
EOF
}
printf '\xef\xbb\xbfx,y,z,radius\n0,0,0,0.001\n' >pbom.csv
csv_scene pbom
accepted pbom "particle CSV with a BOM"
printf 'x,y,z,radius\n0,0\x00,0,0.001\n' >pnul.csv
csv_scene pnul
refused pnul "pnul.csv:2" "NUL byte"
mkdir pdir.csv
csv_scene pdir
refused pdir "pdir.csv' is a directory"

# --- truncated ASCII STL: the floor cut inside each facet --------------------
full=$(wc -c <floor.stl)
f1=$(grep -bo ' endfacet' floor.stl | head -1 | cut -d: -f1)
f2=$(grep -bo ' facet normal' floor.stl | sed -n 2p | cut -d: -f1)
for cut in $((f1 + 4)) $((f2 + 8)) $((f2 + 30)) $((full - 20)); do
    head -c "$cut" floor.stl >cut$cut.stl
    mesh_scene cut$cut "file: cut$cut.stl"
    refused cut$cut "cut$cut.stl ends inside facet" "truncated"
done
mesh_scene whole "file: floor.stl"
accepted whole "the whole floor"

# --- check's mesh line; units ------------------------------------------------
floor mm.stl 30 # a 60 mm floor in millimetres, read as 60 m
mesh_scene mm "file: mm.stl"
out=$("$exe" check mm.yaml 2>&1)
rc=$?
ok=1
[[ $rc == 0 ]] || ok=0
[[ $out == *"mesh         w: 2 facets, box [-30, -30, 0] to [30, 30, 0] m, 60 m across"* ]] || ok=0
[[ $out == *"warning      mesh w is 60 m across, 3e+04 times the largest particle diameter"*"check the units (\`scale:\`"* ]] || ok=0
report $ok "mesh in millimetres" "exit $rc: $(printf '%s\n' "$out" | grep -E '^(mesh|warning +mesh)')"
mesh_scene mmscaled "file: mm.stl, scale: 0.001"
out=$("$exe" check mmscaled.yaml 2>&1)
ok=1
[[ $out == *"mesh         w: 2 facets"*"0.06 m across (30 particle diameters)"* && $out != *"check the units"* ]] || ok=0
report $ok "the same with scale: 0.001" "$(printf '%s\n' "$out" | grep -E '^mesh')"
mesh_scene tiny "file: floor.stl, scale: 1e-300"
refused tiny "wrong units (check scale:)"
python3 - <<'EOF'
s = "solid far\n"
for tri in [((0, 0, 0), (0.01, 0, 0), (0, 0.01, 0)), ((0, 0, 0), (0.01, 0, 0), (0, 0, 1e99))]:
    s += " facet normal 0 0 1\n  outer loop\n" + "".join("   vertex %r %r %r\n" % v for v in tri)
    s += "  endloop\n endfacet\n"
open("far.stl", "w").write(s + "endsolid far\n")
EOF
mesh_scene far "file: far.stl"
refused far "a vertex far from the others, or wrong units (check scale:)"

# --- analysis size in check ---------------------------------------------------
cat >an.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 20000}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0], radius: 0.001}]}]
output: {formats: [csv]}
analysis: [{type: speed_pdf, bins: 10000, every: 1}]
EOF
out=$("$exe" check an.yaml 2>&1)
ok=1
[[ $out == *"analysis     about "*" in 1 file"* && $out == *"warning      the analysis files would hold about"* ]] || ok=0
report $ok "analysis size estimated and warned" "$(printf '%s\n' "$out" | grep -E 'analysis')"

# --- insertion regions across and outside the walls ---------------------------
cat >reg.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 50}
materials: [{name: g, density: 2500, youngs_modulus: 1.0e7}]
walls: [{name: box, type: box, min: [0, 0, 0], max: [0.02, 0.02, 0.05], open: [zmax], material: g}]
output: {formats: []}
insert:
  - {name: across, region: box, min: [-0.01, 0.003, 0.02], max: [0.01, 0.017, 0.04], count: 40, rate: 20000, mix: [{material: g, radius: 0.001}]}
  - {name: far, region: box, min: [1, 1, 1], max: [1.01, 1.01, 1.01], count: 4, mix: [{material: g, radius: 0.001}]}
  - {name: above, region: box, min: [0.002, 0.002, 0.002], max: [0.018, 0.018, 0.06], count: 4, mix: [{material: g, radius: 0.001}]}
EOF
out=$("$exe" check reg.yaml 2>&1)
ok=1
[[ $out == *"warning      insertion across: its region reaches 0.01 m beyond the closed face xmin of wall 'box'"* ]] || ok=0
[[ $out == *"warning      insertion far: its region lies outside wall 'box'"*"no particle can be placed"* ]] || ok=0
[[ $out != *"insertion above"* ]] || ok=0 # across the open top: no warning
report $ok "insertion regions against the walls" "$(printf '%s\n' "$out" | grep -E 'insertion (across|far|above)')"

finish input_bounds
