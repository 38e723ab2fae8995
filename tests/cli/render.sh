#!/usr/bin/env bash
# render.sh — `shapedem render` (src/render/, docs/output.md):
#  - one scene per particle kind (sphere, convex, polyhedron, planar,
#    composite; tests/render/kinds.sh) runs with output.formats: [vtk, shapes]
#    and renders, from its frames.pvd, a PNG of exactly the requested size;
#  - tests/render/simple.yaml's picture matches tests/render/simple_ref.png:
#    the mean absolute difference (0-255, after a 3x3 blur,
#    tests/render/png_mad.py) is below TOL for the same picture and for the
#    picture moved one pixel, and above TOL for the picture drawn with
#    another colour map (gray; coolwarm);
#  - a frames.pvd --movie writes one numbered PNG per frame;
#  - a categorical field (shape, material) is drawn with a legend naming
#    its values, a scale with its unit, and render says what it drew;
#  - --fit all frames the bounded walls, not a plane that moved away;
#  - a frames.pvd of 100,000 entries renders within 250 MB of address space;
#  - bad input (a file that is not a frame, a missing file, a bad --size, a
#    field the frame lacks, --frame past the end) is one line on stderr
#    naming the file or option, exit 2, and no picture.
# Without rendering in the build (no cairo) the command must say so, exit 2.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
py=/usr/bin/python3
mad="$root/tests/render/png_mad.py"
TOL=6.0

"$bin" render "$root/tests/render/simple.yaml" -o "$tmp/x.png" 2>"$tmp/probe.err"
if grep -q "built without rendering" "$tmp/probe.err"; then
    check "a build without cairo says so and exits 2" "$([[ $(wc -l <"$tmp/probe.err") == 1 ]] && echo 1 || echo 0)"
    echo "$pass passed, $fail failed (render not built: the rest skipped)"
    exit $((fail > 0))
fi

bash "$root/tests/render/kinds.sh" "$tmp"
for k in sphere convex polyhedron planar composite; do
    "$bin" run "$tmp/$k.yaml" -o "$tmp/$k" --quiet >/dev/null 2>"$tmp/$k.err"
    rc=$?
    "$bin" render "$tmp/$k/frames.pvd" -o "$tmp/$k.png" --size 123x77 2>>"$tmp/$k.err"
    rc2=$?
    size=$("$py" "$mad" size "$tmp/$k.png" 2>/dev/null)
    check "$k: run exit $rc, render exit $rc2, PNG $size (123 77), shapes file written" \
        "$([[ $rc == 0 && $rc2 == 0 && $size == "123 77" && -f $tmp/$k/shapes_000000.vtp ]] && echo 1 || echo 0)"
    [[ -s $tmp/$k.err ]] && head -3 "$tmp/$k.err"
done

# The shapes file's XML header is well-formed XML (Python's parser, up to the raw data).
"$py" - "$tmp/polyhedron/shapes_000000.vtp" >"$tmp/xml.out" 2>&1 <<'EOF'
import sys, xml.etree.ElementTree as ET
data = open(sys.argv[1], "rb").read()
head = data[:data.index(b"<AppendedData")].decode() + "</VTKFile>"
root = ET.fromstring(head)
piece = root.find("PolyData/Piece")
names = [a.get("Name") for a in root.iter("DataArray")]
print(root.get("type"), piece.get("NumberOfPolys"), ",".join(names))
EOF
echo "     shapes header: $(cat "$tmp/xml.out")"
check "the shapes file's header parses as XML: PolyData, cells, id ... shape, position, connectivity, offsets" \
    "$(grep -q '^PolyData [1-9][0-9]* id,radius,velocity,angular_velocity,force,material,orientation,axis,shape,position,connectivity,offsets$' "$tmp/xml.out" && echo 1 || echo 0)"

# The reference picture: same options as when simple_ref.png was made.
"$bin" run "$root/tests/render/simple.yaml" -o "$tmp/simple" --quiet >/dev/null
opts=(--size 160x120 --no-colorbar --field radius --range 0.001,0.003 --view iso)
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/simple.png" "${opts[@]}"
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/gray.png" "${opts[@]}" --colormap gray
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/coolwarm.png" "${opts[@]}" --colormap coolwarm
ref="$root/tests/render/simple_ref.png"
same=$("$py" "$mad" mad "$ref" "$tmp/simple.png")
shift1=$("$py" "$mad" mad "$ref" "$tmp/simple.png" --shift 1)
gray=$("$py" "$mad" mad "$ref" "$tmp/gray.png")
warm=$("$py" "$mad" mad "$ref" "$tmp/coolwarm.png")
lt() { awk -v a="$1" -v b="$2" 'BEGIN { print (a + 0 < b + 0) ? 1 : 0 }'; }
check "reference picture: MAD $same < $TOL" "$(lt "$same" $TOL)"
check "reference picture moved one pixel: MAD $shift1 < $TOL (passes)" "$(lt "$shift1" $TOL)"
check "reference picture in the gray map: MAD $gray > $TOL (fails)" "$(lt $TOL "$gray")"
check "reference picture in the coolwarm map: MAD $warm > $TOL (fails)" "$(lt $TOL "$warm")"

# A categorical field gets a legend of names, not a colour scale (issue 31):
# simple.yaml's 3 spheres, cube and rod by shape; the bar's column holds the
# three swatches' colours only (a scale's gradient holds hundreds).
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/shape.png" --field shape >"$tmp/shape.out" 2>&1
rc=$?
legend=$("$py" "$mad" colours "$tmp/shape.png" 710)
echo "     $(head -1 "$tmp/shape.out"); legend column colours (10 px or more, all): $legend"
check "--field shape: exit $rc, the names and counts of the shapes" \
    "$([[ $rc == 0 ]] && grep -q 'coloured by shape: sphere (3), cube (1), rod (1)$' "$tmp/shape.out" && echo 1 || echo 0)"
check "--field shape: a legend of 3 swatches (got '$legend'), not a gradient" "$([[ $legend == "3 3" ]] && echo 1 || echo 0)"
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/speed.png" >"$tmp/speed.out" 2>&1
scale=$("$py" "$mad" colours "$tmp/speed.png" 710)
check "--field speed: a colour scale (got '$scale' colours, more than 100) in m/s" \
    "$([[ ${scale#* } -gt 100 ]] && grep -q 'coloured by speed, .* m/s$' "$tmp/speed.out" && echo 1 || echo 0)"
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/force.png" --field force >"$tmp/force.out" 2>&1
"$bin" render "$tmp/simple/frames.pvd" -o "$tmp/mat.png" --field material >"$tmp/mat.out" 2>&1
check "--field force names N, --field material names the material" \
    "$(grep -q 'coloured by force, .* N$' "$tmp/force.out" && grep -q 'coloured by material: glass (5)$' "$tmp/mat.out" &&
        echo 1 || echo 0)"

# --fit all frames the bounded walls, not a plane that moved away (issue
# 31): simple.yaml with a lid plane moving up 0.34 m in 10 steps; the
# particles (the coloured pixels) keep most of the picture's width.
sed -e 's/steps: 1$/steps: 10/' -e 's/  every: 1$/  every: 10/' \
    -e 's/^\(  - {name: tray.*\)$/\1\n  - {name: lid, type: plane, point: [0, 0, 0.01], normal: [0, 0, -1], velocity: [0, 0, 34000], material: glass}/' \
    "$root/tests/render/simple.yaml" >"$tmp/lid.yaml"
"$bin" run "$tmp/lid.yaml" -o "$tmp/lid" --quiet >/dev/null
"$bin" render "$tmp/lid/frames.pvd" -o "$tmp/lid.png" --fit all --no-colorbar --size 200x150 >/dev/null
read -r x0 _ x1 _ <<<"$("$py" "$mad" extent "$tmp/lid.png")"
echo "     particles drawn from x = $x0 to $x1 of 200"
check "--fit all with a plane 0.34 m away: the particles span $((x1 - x0)) of 200 px (at least 80)" \
    "$([[ $((x1 - x0)) -ge 80 ]] && echo 1 || echo 0)"

# A particle frame under another name (no siblings to look for): spheres, and a note.
cp "$tmp/simple/particles_000000.vtu" "$tmp/a.vtu"
"$bin" render "$tmp/a.vtu" -o "$tmp/a.png" --size 64x48 2>"$tmp/a.err"
rc=$?
check "a frame named a.vtu: exit $rc, a picture, the bounding-sphere note on stderr" \
    "$([[ $rc == 0 && -s $tmp/a.png ]] && grep -q "bounding spheres" "$tmp/a.err" && echo 1 || echo 0)"

# A movie of a two-frame run.
"$bin" run "$root/tests/render/simple.yaml" -o "$tmp/two" --steps 2 --quiet >/dev/null
mkdir -p "$tmp/movie"
"$bin" render "$tmp/two/frames.pvd" --movie -o "$tmp/movie/m.png" --size 64x48 >"$tmp/movie.out" 2>&1
rc=$?
n=$(ls "$tmp/movie" | grep -c '^m_00000[0-9]\.png$')
frames=$(grep -c 'part="0"' "$tmp/two/frames.pvd")
check "--movie: exit $rc, $n pictures for $frames frames" "$([[ $rc == 0 && $n == "$frames" && $n -ge 2 ]] && echo 1 || echo 0)"

# Bad input: one line, exit 2, nothing written.
bad() { # label, expected text, args...
    local label="$1" want="$2"
    shift 2
    rm -f "$tmp/bad.png"
    "$bin" render "$@" >"$tmp/bad.out" 2>"$tmp/bad.err"
    local rc=$?
    echo "     $(head -1 "$tmp/bad.err")"
    check "bad input: $label: exit $rc (2), one line naming it, no picture" \
        "$([[ $rc == 2 && $(wc -l <"$tmp/bad.err") == 1 && ! -s $tmp/bad.out && ! -e $tmp/bad.png ]] &&
            grep -q -- "$want" "$tmp/bad.err" && echo 1 || echo 0)"
}
bad "a scene file given as a frame" "simple.yaml: not a shapedem frame" "$root/tests/render/simple.yaml" -o "$tmp/bad.png"
bad "a missing file" "no_such_frame.vtu" "$tmp/no_such_frame.vtu" -o "$tmp/bad.png"
bad "--size 12x" "--size" "$tmp/simple/particles_000000.vtu" -o "$tmp/bad.png" --size 12x
bad "--size 0x100" "--size" "$tmp/simple/particles_000000.vtu" -o "$tmp/bad.png" --size 0x100
bad "a field the frame lacks" "no field 'temperature'" "$tmp/simple/particles_000000.vtu" -o "$tmp/bad.png" --field temperature
bad "--frame past the end" "--frame 5" "$tmp/simple/frames.pvd" -o "$tmp/bad.png" --frame 5
full=$(wc -c <"$tmp/simple/shapes_000000.vtp")
head -c 300 "$tmp/simple/shapes_000000.vtp" >"$tmp/shapes_000008.vtp"
head -c $((full - 1000)) "$tmp/simple/shapes_000000.vtp" >"$tmp/shapes_000009.vtp"
bad "a shapes file cut in its header" "not a shapedem frame" "$tmp/shapes_000008.vtp" -o "$tmp/bad.png"
bad "a shapes file cut in its data" "not a shapedem frame: an array" "$tmp/shapes_000009.vtp" -o "$tmp/bad.png"

# a frames.pvd of 100,000 entries (all naming one frame) renders its last
# within 250 MB of address space: the list of frames costs what its names
# do, not a fixed 4 KB an entry (420 MB before; probe 3, low findings)
{ sed -n '1,/<Collection>/p' "$tmp/simple/frames.pvd"
  entry=$(grep -m1 'part="0"' "$tmp/simple/frames.pvd")
  for ((k = 0; k < 100000; ++k)); do echo "$entry"; done
  sed -n '/<\/Collection>/,$p' "$tmp/simple/frames.pvd"; } >"$tmp/simple/big.pvd"
if ldd "$bin" 2>/dev/null | grep -q libasan; then
    echo "SKIP the 100,000-frame frames.pvd: a sanitizer build reserves more address space than the limit"
else
    (ulimit -v 250000; "$bin" render "$tmp/simple/big.pvd" -o "$tmp/big.png" >/dev/null 2>"$tmp/big.err")
    rc=$?
    check "a 100,000-frame frames.pvd renders in 250 MB of address space (exit $rc: $(head -c 200 "$tmp/big.err"))" \
        "$([[ $rc == 0 && -s $tmp/big.png ]] && echo 1 || echo 0)"
fi

finish
