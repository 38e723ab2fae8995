#!/usr/bin/env bash
# checkpoint_look.sh — a checkpoint can be looked at without HDF5 tools
# (issue 31: `render` refused a failed-NNNNNN.h5 and nothing installed reads
# HDF5):
#  - `shapedem info CK.h5 --csv` lists its particles: one row per particle
#    (the count `info` reports), and every position, velocity, spin,
#    orientation and radius equals the frame written at the same step, bit
#    for bit (the frame's Float64 arrays read with Python's struct);
#  - `shapedem render CK.h5` draws it (exit 0, a PNG of the asked size, the
#    note that it draws spheres), coloured by shape with the names kept in
#    the checkpoint; with --scene (the scene that wrote it) the restored
#    world is drawn with true shapes and walls: the picture of the frame of
#    the same step, and no temporary file left;
#  - bad input: a scene given to info --csv, a truncated checkpoint, a field
#    the checkpoint lacks, --scene of another scene or with a frame: one line
#    on stderr, exit 2, nothing on stdout and no picture.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
py=/usr/bin/python3

# simple.yaml (3 spheres, a cube, a rod) for 20 steps: a frame and a checkpoint at step 20
sed -e 's/steps: 1$/steps: 20/' -e 's/  every: 1$/  every: 10\n  checkpoint_every: 10/' \
    "$root/tests/render/simple.yaml" >"$tmp/s.yaml"
"$bin" run "$tmp/s.yaml" -o "$tmp/run" --quiet >/dev/null 2>"$tmp/run.err"
ck="$tmp/run/checkpoint-000020.h5"
check "the run wrote checkpoint-000020.h5 and particles_000002.vtu (step 20)" \
    "$([[ -s $ck && -s $tmp/run/particles_000002.vtu ]] && echo 1 || echo 0)"

"$bin" info "$ck" --csv >"$tmp/p.csv" 2>"$tmp/csv.err"
rc=$?
n=$(awk '/^particles / {print $2}' <<<"$("$bin" info "$ck")")
rows=$(($(wc -l <"$tmp/p.csv") - 1))
echo "     $(head -1 "$tmp/p.csv")"
check "info --csv: exit $rc, $rows rows for the $n particles info reports" \
    "$([[ $rc == 0 && -n $n && $rows == "$n" && ! -s $tmp/csv.err ]] && echo 1 || echo 0)"
"$bin" info "$ck" --particles csv >"$tmp/p2.csv" 2>/dev/null
check "info --particles csv: the same rows" "$(cmp -s "$tmp/p.csv" "$tmp/p2.csv" && echo 1 || echo 0)"

# every value against the frame of step 20, by id
"$py" - "$tmp/run/particles_000002.vtu" "$tmp/p.csv" >"$tmp/cmp.out" 2>&1 <<'EOF'
import csv, re, struct, sys
data = open(sys.argv[1], "rb").read()
head = data[:data.index(b"<AppendedData")].decode()
base = data.index(b"_", data.index(b"<AppendedData")) + 1
arrays = {}
for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"(?: NumberOfComponents="(\d+)")? format="appended" offset="(\d+)"', head):
    kind, name, comps, off = m.group(1), m.group(2), int(m.group(3) or 1), int(m.group(4))
    nbytes = struct.unpack_from("<Q", data, base + off)[0]
    fmt = {"Float64": "d", "UInt64": "Q", "Int32": "i", "Int64": "q", "UInt8": "B"}[kind]
    vals = struct.unpack_from("<%d%s" % (nbytes // struct.calcsize(fmt), fmt), data, base + off + 8)
    arrays[name] = [vals[i:i + comps] for i in range(0, len(vals), comps)]
rows = {int(r["id"]): r for r in csv.DictReader(open(sys.argv[2]))}
cols = {"position": "x y z", "velocity": "vx vy vz", "angular_velocity": "wx wy wz",
        "orientation": "qw qx qy qz", "radius": "radius"}
checked = bad = 0
for k, pid in enumerate(arrays["id"]):
    r = rows[pid[0]]
    for arr, names in cols.items():
        for c, name in enumerate(names.split()):
            checked += 1
            if float(r[name]) != arrays[arr][k][c]:
                bad += 1
                print("differs: id", pid[0], name, r[name], arrays[arr][k][c])
print(len(arrays["id"]), len(rows), checked, bad)
EOF
read -r fn cn checked bad <<<"$(tail -1 "$tmp/cmp.out")"
echo "     frame particles $fn, CSV rows $cn, values compared $checked, differing $bad"
check "info --csv equals the step-20 frame bit for bit ($checked values, $bad differ)" \
    "$([[ $fn == "$cn" && ${checked:-0} -gt 0 && $bad == 0 ]] && echo 1 || echo 0)"
check "info --csv names the shapes (cube, rod; empty for the spheres) and the material" \
    "$(awk -F, 'NR > 1 {print $16 "/" $17}' "$tmp/p.csv" | sort | tr '\n' ' ' | grep -q '^/glass /glass /glass cube/glass rod/glass $' &&
        echo 1 || echo 0)"

# render the checkpoint
"$bin" render "$ck" -o "$tmp/ck.png" --size 160x120 --field shape >"$tmp/r.out" 2>"$tmp/r.err"
rc=$?
size=$("$py" "$root/tests/render/png_mad.py" size "$tmp/ck.png" 2>/dev/null)
echo "     $(cat "$tmp/r.out")"
check "render CK.h5: exit $rc, PNG $size (160 120), coloured by the shapes' names, the spheres note" \
    "$([[ $rc == 0 && $size == "160 120" ]] && grep -q 'coloured by shape: sphere (3), cube (1), rod (1)$' "$tmp/r.out" &&
        grep -q 'is a checkpoint: its particles are drawn as spheres' "$tmp/r.err" && echo 1 || echo 0)"

# with the scene that wrote it: the restored world's true shapes and walls,
# the same picture as the run's frame of step 20; no temporary left behind
mkdir -p "$tmp/t"
TMPDIR="$tmp/t" "$bin" render "$ck" --scene "$tmp/s.yaml" -o "$tmp/cks.png" --size 160x120 --fit all >/dev/null 2>"$tmp/cks.err"
rc=$?
"$bin" render "$tmp/run/particles_000002.vtu" -o "$tmp/frame.png" --size 160x120 --fit all >/dev/null 2>&1
mad=$("$py" "$root/tests/render/png_mad.py" mad "$tmp/frame.png" "$tmp/cks.png" 2>&1)
"$bin" render "$ck" -o "$tmp/cksph.png" --size 160x120 --fit all >/dev/null 2>&1
sph=$("$py" "$root/tests/render/png_mad.py" mad "$tmp/frame.png" "$tmp/cksph.png" 2>&1)
check "render CK.h5 --scene: exit $rc, the step-20 frame's picture (MAD $mad < 0.5; spheres only: $sph), no temporary left" \
    "$([[ $rc == 0 && ! -s $tmp/cks.err && -z $(ls -A "$tmp/t") ]] &&
        awk -v a="$mad" -v b="$sph" 'BEGIN { print (a + 0 < 0.5 && b + 0 > 0.5) ? 1 : 0 }' || echo 0)"

# bad input: one line, exit 2, nothing on stdout, no picture
bad() { # label, expected text, command...
    local label="$1" want="$2"
    shift 2
    rm -f "$tmp/bad.png"
    "$bin" "$@" >"$tmp/bad.out" 2>"$tmp/bad.err"
    local rc=$?
    echo "     $(head -1 "$tmp/bad.err")"
    check "bad input: $label: exit $rc (2), one line naming it, nothing on stdout, no picture" \
        "$([[ $rc == 2 && $(wc -l <"$tmp/bad.err") == 1 && ! -s $tmp/bad.out && ! -e $tmp/bad.png ]] &&
            grep -q -- "$want" "$tmp/bad.err" && echo 1 || echo 0)"
}
head -c 3000 "$ck" >"$tmp/cut.h5"
bad "info --csv of a scene" "s.yaml: not a shapedem checkpoint" info "$tmp/s.yaml" --csv
bad "info --csv of a truncated checkpoint" "cut.h5" info "$tmp/cut.h5" --csv
bad "render of a truncated checkpoint" "cut.h5" render "$tmp/cut.h5" -o "$tmp/bad.png"
bad "render a field the checkpoint lacks" "no field 'temperature'" render "$ck" -o "$tmp/bad.png" --field temperature
bad "info --cvs (a typo)" "unknown option '--cvs'" info "$ck" --cvs
sed 's/density: 2500/density: 2600/' "$tmp/s.yaml" >"$tmp/other.yaml"
bad "render --scene with another scene" "written by another scene" render "$ck" --scene "$tmp/other.yaml" -o "$tmp/bad.png"
bad "--scene with a frame" "--scene goes with a checkpoint" render "$tmp/run/particles_000002.vtu" --scene "$tmp/s.yaml" -o "$tmp/bad.png"

finish checkpoint_look
