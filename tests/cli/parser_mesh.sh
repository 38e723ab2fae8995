#!/usr/bin/env bash
# parser_mesh.sh — the OBJ and STL readers' messages (robustness probe
# F13): a non-finite binary STL coordinate names the file's facet, numbers
# out of a double's range are called that, upper-case STL keywords are
# read, and file bytes are echoed escaped. Each refusal is exit 2 with one
# stderr line naming the scene, the line of shapes[0].file and the key.
#
# Usage: bash parser_mesh.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: parser_mesh.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_parser_mesh.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
pass=0
fail=0
report() { # report 1|0 name detail
    if [[ $1 == 1 ]]; then pass=$((pass + 1)); echo "PASS $2: $3"; else fail=$((fail + 1)); echo "FAIL $2: $3"; fi
}

# scene NAME MESH [EXTRA]: NAME.yaml with one shape from MESH at line 3.
scene() {
    cat >"$1.yaml" <<EOF
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes: [{name: s, type: polyhedron, file: $2${3:-}}]
particles: [{generator: list, material: m, spheres: [{position: [0, 0, 0], shape: s}]}]
EOF
}

# refused NAME TEXT...: `check NAME.yaml` exits 2 with one line holding
# NAME.yaml:3: shapes[0].file: and each TEXT.
refused() {
    local name=$1 err rc n ok=1
    shift
    err=$("$exe" check "$name.yaml" 2>&1 >/dev/null)
    rc=$?
    n=$(printf '%s\n' "$err" | wc -l)
    [[ $rc == 2 && $n == 1 && $err == *"$name.yaml:3: shapes[0].file: "* ]] || ok=0
    for text in "$@"; do [[ $err == *"$text"* ]] || ok=0; done
    report $ok "$name" "exit $rc, $n line(s): $err"
}

# A binary STL tetrahedron (1 cm) with one coordinate replaced.
python3 - <<'EOF'
import struct
v = [(0, 0, 0), (0.01, 0, 0), (0, 0.01, 0), (0, 0, 0.01)]
f = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
def stl(name, bad=None):
    b = bytearray(80) + struct.pack('<I', len(f))
    for i, tri in enumerate(f):
        b += struct.pack('<3f', 0, 0, 0)
        for j, k in enumerate(tri):
            p = list(v[k])
            if bad and bad[:2] == (i, j):
                p[1] = bad[2]
            b += struct.pack('<3f', *p)
        b += b'\0\0'
    open(name, 'wb').write(b)
stl('good.stl')
stl('nan.stl', (2, 2, float('nan')))
stl('inf.stl', (3, 0, float('inf')))
EOF
scene good good.stl
"$exe" check good.yaml >/dev/null 2>&1
report "$([[ $? == 0 ]] && echo 1 || echo 0)" "binary STL tetrahedron" "accepted"
scene nan nan.stl
refused nan "facet 3 of 4 in 'nan.stl'" "not finite"
# with nonconvex: hull the message was about "vertices: vertex 3"
scene inf inf.stl ", nonconvex: hull"
refused inf "facet 4 of 4 in 'inf.stl'" "not finite"

# ASCII STL: keywords in upper case, as some writers emit them.
{
    echo "SOLID T"
    for tri in "0 0 0|0 0.01 0|0.01 0 0" "0 0 0|0.01 0 0|0 0 0.01" "0 0 0|0 0 0.01|0 0.01 0" "0.01 0 0|0 0.01 0|0 0 0.01"; do
        echo " FACET NORMAL 0 0 0"
        echo "  OUTER LOOP"
        IFS='|' read -r a b c <<<"$tri"
        printf '   VERTEX %s\n   VERTEX %s\n   VERTEX %s\n' "$a" "$b" "$c"
        echo "  ENDLOOP"
        echo " ENDFACET"
    done
    echo "ENDSOLID T"
} >upper.stl
scene upper upper.stl
out=$("$exe" check upper.yaml 2>&1)
report "$([[ $? == 0 ]] && echo 1 || echo 0)" "ASCII STL with upper-case VERTEX" "$(tail -1 <<<"$out")"

# Numbers beyond a double: overflow and underflow, named as such.
printf 'v 0 0 0\nv 1e400 0 0\nv 0 1 0\nv 0 0 1\n' >over.obj
scene over over.obj
refused over "over.obj line 2: coordinate 1e400 is too large for a double"
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1e-400 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n' >under.stl
scene under under.stl
refused under "under.stl line 5: coordinate 1e-400 is too small for a double"

printf 'v 0 0 0\nv 1 0 0\nv 0 NaN 0\nv 0 0 1\n' >nan.obj
scene nanobj nan.obj
refused nanobj "nan.obj line 3: coordinate NaN is not finite"

# C's hexadecimal floats are refused, as in scenes and outline CSVs.
printf 'v 0x1p-7 0 0\nv 0.01 0 0\nv 0 0.01 0\nv 0 0 0.01\n' >hex.obj
scene hexobj hex.obj
refused hexobj "hex.obj line 1: hexadecimal numbers (0x...) are not accepted"

# Raw bytes of the file (an ANSI colour and a carriage return) come back
# escaped, never as bytes that act on the terminal.
printf 'v 0 0 0\nv 0.01 0 0\nv 0 0.01 0\nv 0 0 0.01\nf 1 2 \033[31mRED\r\n' >esc.obj
scene esc esc.obj
refused esc "esc.obj line 5: a face names vertex '\\x1b[31mRED\\r'"
if LC_ALL=C grep -q $'[\e\r]' <<<"$("$exe" check esc.yaml 2>&1)"; then
    report 0 "no raw ESC or CR on stderr" "found one"
else
    report 1 "no raw ESC or CR on stderr" "none"
fi

echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
