#!/usr/bin/env bash
# planar_fit_robust.sh — the robustness probe's reproducers for
# `shapedem shape fit-fourier` and 2D polygons (findings F2, F9, F10, F13):
#   - outlines that crashed (a coordinate >= 1.3e155, all points 1e-160) or
#     printed impossible coverage (a bow-tie: -inf %; a 1 x 1e-12 sliver; a
#     10^5-point random cloud: 193 %) are refused: exit 2, one stderr line
#     naming the file, nothing on stdout;
#   - a 2 cm circle at (1e8, 1e8) (a segfault) and at (1e5, 1e5) (centroid
#     60 m off) fits like one at the origin; a truncated outline and a C
#     shape print a coverage within [0, 100] %;
#   - a 10^6-point circle fits (it took 23 s: no time is asserted here, the
#     test only runs it); --beta 0.999999999999 (an unbounded loop) is
#     refused, --beta 0.99 at order 64 finishes;
#   - hexadecimal numbers are refused naming the line; a row of terminal
#     escapes or binary garbage is quoted escaped (no raw control bytes);
#   - a 2D polygon of 1000 points on a circle of radius 1e160 (it smashed
#     the stack) is refused by `check` naming file, line and key; a polygon
#     given around (1e5, 1e5) gets its true centre of mass and moments.
# Usage: bash planar_fit_robust.sh SHAPEDEM REPO
set -u
bin="$1"
root="$2"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_planar_fit.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
field() { # field NAME OUTPUT: the first number after the label
    awk -v k="$1" '$1 == k { gsub(/[(,]/, " "); print $2; exit }' <<<"$2"
}

# refused NAME EXPECTED-TEXT FILE [ARGS...]: exit 2, one stderr line with the file and the text, no stdout
refused() {
    local name=$1 want=$2 file=$3
    shift 3
    "$bin" shape fit-fourier "$file" "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$? nerr nout ok=0
    nerr=$(wc -l <"$tmp/err")
    nout=$(wc -c <"$tmp/out")
    [[ $rc == 2 && $nerr == 1 && $nout == 0 ]] && grep -qF -- "$(basename "$file")" "$tmp/err" &&
        grep -qF -- "$want" "$tmp/err" && ok=1
    check "$name: exit 2, one line naming the file with '$want' (rc $rc: $(head -c 300 "$tmp/err"))" "$ok"
}
# fits NAME FILE [ARGS...]: exit 0; sets out
fits() {
    local name=$1 file=$2
    shift 2
    out=$("$bin" shape fit-fourier "$file" "$@" 2>"$tmp/err")
    local rc=$?
    check "$name: exit 0 (rc $rc: $(head -c 300 "$tmp/err"))" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
}
in_range() { awk -v v="$1" -v lo="$2" -v hi="$3" 'BEGIN { print (v != "" && v + 0 >= lo && v + 0 <= hi) ? 1 : 0 }'; }
circle() { # circle N CX CY R
    awk -v n="$1" -v cx="$2" -v cy="$3" -v r="$4" 'BEGIN { pi = atan2(0, -1)
        for (i = 0; i < n; ++i) printf "%.17g,%.17g\n", cx + r * cos(2 * pi * i / n), cy + r * sin(2 * pi * i / n) }'
}

# ---- F2: overflow, underflow, far from the origin -------------------------------------
printf '0,0\n1e155,0\n1e155,1e155\n0,1e155\n' >"$tmp/big.csv"
refused "square of side 1e155" "spans 1e+155 m" "$tmp/big.csv" --order 8
awk -F, 'NR == 10 && $0 !~ /^#/ { $0 = "1.3e155," $2 } { print }' "$root/tests/cli/outlines/rock.csv" >"$tmp/rock-big.csv"
refused "rock.csv with one coordinate 1.3e155" "over- or underflow" "$tmp/rock-big.csv" --order 8
printf '0,0\n1e-160,0\n1e-160,1e-160\n0,1e-160\n' >"$tmp/tiny.csv"
refused "every point 1e-160" "spans 1e-160 m" "$tmp/tiny.csv" --order 8
for c in 1e5 1e8; do
    circle 720 "$c" "$c" 0.02 >"$tmp/far$c.csv"
    fits "2 cm circle at ($c, $c)" "$tmp/far$c.csv" --order 8
    ox=$(field origin "$out")
    check "2 cm circle at ($c, $c): origin x = $c within 1e-6 m (got $ox)" \
        "$(awk -v v="$ox" -v c="$c" 'BEGIN { d = v - c; if (d < 0) d = -d; print (v != "" && d <= 1e-6) }')"
    cov=$(field coverage "$out")
    check "2 cm circle at ($c, $c): coverage in [99.99, 100] % (got $cov)" "$(in_range "$cov" 99.99 100)"
done
circle 720 1e12 1e12 0.02 >"$tmp/far1e12.csv"
refused "2 cm circle at (1e12, 1e12)" "significant digits" "$tmp/far1e12.csv"

# ---- F9: outlines with no meaningful coverage ---------------------------------------------
printf '0,0\n1,1\n1,0\n0,1\n' >"$tmp/bowtie.csv"
refused "bow-tie" "crosses or touches itself" "$tmp/bowtie.csv"
printf '0,0\n1,0\n1,1e-12\n0,1e-12\n' >"$tmp/sliver.csv"
refused "1 x 1e-12 sliver" "flat" "$tmp/sliver.csv"
awk 'BEGIN { srand(1); for (i = 0; i < 100000; ++i) printf "%.9f,%.9f\n", rand(), rand() }' >"$tmp/cloud.csv"
refused "random cloud of 10^5 points" "crosses or touches itself" "$tmp/cloud.csv"
# a truncated outline: the rock's first 70 lines
head -n 70 "$root/tests/cli/outlines/rock.csv" >"$tmp/half.csv"
fits "truncated rock" "$tmp/half.csv"
cov=$(field coverage "$out")
check "truncated rock: coverage in [0, 100] % (got $cov)" "$(in_range "$cov" 0 100)"
# a C shape: the convex fit covers its hole, the difference exceeds its area
awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i <= 300; ++i) printf "%.12f,%.12f\n", cos((30 + i) * pi / 180), sin((30 + i) * pi / 180)
             for (i = 300; i >= 0; --i) printf "%.12f,%.12f\n", 0.9 * cos((30 + i) * pi / 180), 0.9 * sin((30 + i) * pi / 180) }' >"$tmp/c.csv"
fits "C shape" "$tmp/c.csv"
cov=$(field coverage "$out")
check "C shape: coverage 0 % (floored), with a note (got $cov)" \
    "$([[ $(in_range "$cov" 0 0) == 1 ]] && grep -q '^note .*more than the outline' <<<"$out" && echo 1 || echo 0)"

# ---- F10: bounded work --------------------------------------------------------------------
circle 1000000 0 0 0.02 >"$tmp/circle1m.csv"
fits "10^6-point circle" "$tmp/circle1m.csv"
cov=$(field coverage "$out")
check "10^6-point circle: coverage in [99.99, 100] % (got $cov)" "$(in_range "$cov" 99.99 100)"
"$bin" shape fit-fourier "$root/tests/cli/outlines/rock.csv" --beta 0.999999999999 >"$tmp/out" 2>"$tmp/err"
rc=$?
check "--beta 0.999999999999: exit 2, one line naming --beta (rc $rc: $(head -c 300 "$tmp/err"))" \
    "$([[ $rc == 2 && $(wc -l <"$tmp/err") == 1 && ! -s $tmp/out ]] && grep -qF -- '--beta' "$tmp/err" && echo 1 || echo 0)"
fits "--beta 0.99 at order 64" "$root/tests/cli/outlines/rock.csv" --beta 0.99 --order 64
check "--beta 0.99 at order 64: reduction reported" "$(grep -q '^reduction *needed' <<<"$out" && echo 1 || echo 0)"

# ---- F13: hexadecimal numbers, raw bytes ----------------------------------------------------
printf '0,0\n0x1p-1,0\n1,1\n' >"$tmp/hex.csv"
refused "hexadecimal number" "hex.csv:2: hexadecimal" "$tmp/hex.csv"
printf '0,0\n1,0\nf 1 2 \033[31mRED\r\n' >"$tmp/ansi.csv"
refused "row with an ANSI escape and a CR" 'ansi.csv:3:' "$tmp/ansi.csv"
check "row with an ANSI escape and a CR: quoted escaped, no raw ESC or CR ($(cat "$tmp/err"))" \
    "$(grep -qF '\x1b[31mRED' "$tmp/err" && ! LC_ALL=C grep -q $'[\x01-\x08\x0b-\x1f\x7f]' "$tmp/err" && echo 1 || echo 0)"
printf '0,0\n\001\002\377\376garbage\033c\n' >"$tmp/garbage.csv"
refused "row of binary garbage" 'garbage.csv:2:' "$tmp/garbage.csv"
check "row of binary garbage: only printable ASCII on stderr" \
    "$(LC_ALL=C grep -q $'[^\t -~]' <(tr -d '\n' <"$tmp/err") && echo 0 || echo 1)"

# ---- F2 in a 2D scene -------------------------------------------------------------------------
scene() { # scene FILE N R CX
    awk -v n="$2" -v r="$3" -v c="$4" 'BEGIN { pi = atan2(0, -1)
        print "simulation: {dimension: 2, dt: 1.0e-5, steps: 5, gravity: [0, -9.8, 0], contact_law: linear}"
        print "materials: [{name: g, density: 2700, stiffness: 1.0e6}]"
        printf "shapes: [{name: p, type: polygon, points: ["
        for (i = 0; i < n; ++i) printf "%s[%.17g, %.17g]", i ? ", " : "", c + r * cos(2 * pi * i / n), c + r * sin(2 * pi * i / n)
        print "]}]"
        print "particles: [{generator: list, material: g, spheres: [{position: [0, 0, 0], shape: p}]}]" }' >"$1"
}
scene "$tmp/poly.yaml" 1000 1e160 0
"$bin" check "$tmp/poly.yaml" >"$tmp/out" 2>"$tmp/err"
rc=$?
check "1000-point polygon of radius 1e160: check exits 2 with poly.yaml:3: shapes[0].points (rc $rc: $(head -c 300 "$tmp/err"))" \
    "$([[ $rc == 2 && $(wc -l <"$tmp/err") == 1 ]] && grep -qF 'poly.yaml:3: shapes[0].points' "$tmp/err" && echo 1 || echo 0)"
scene "$tmp/near.yaml" 12 0.01 0
scene "$tmp/far.yaml" 12 0.01 1e5
near=$("$bin" shape info "$tmp/near.yaml" 2>&1)
far=$("$bin" shape info "$tmp/far.yaml" 2>&1)
vn=$(field volume "$near")
vf=$(field volume "$far")
jn=$(awk '$1 == "principal" { gsub(/[(,]/, " "); print $3; exit }' <<<"$near")
jf=$(awk '$1 == "principal" { gsub(/[(,]/, " "); print $3; exit }' <<<"$far")
cf=$(awk '$1 == "centre" { gsub(/[(,]/, " "); print $5; exit }' <<<"$far")
check "12-gon at (1e5, 1e5): volume $vf as at the origin ($vn), to 1e-6" \
    "$(awk -v a="$vf" -v b="$vn" 'BEGIN { d = a - b; if (d < 0) d = -d; print (b > 0 && d <= 1e-6 * b) }')"
check "12-gon at (1e5, 1e5): moment $jf as at the origin ($jn), to 1e-6" \
    "$(awk -v a="$jf" -v b="$jn" 'BEGIN { d = a - b; if (d < 0) d = -d; print (b > 0 && d <= 1e-6 * b) }')"
check "12-gon at (1e5, 1e5): centre of mass x = 1e5 within 1e-6 m (got $cf)" \
    "$(awk -v v="$cf" 'BEGIN { d = v - 1e5; if (d < 0) d = -d; print (v != "" && d <= 1e-6) }')"

finish
