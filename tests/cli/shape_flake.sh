#!/usr/bin/env bash
# shape_flake.sh — flat and long ellipsoids with a margin or a rounding (the
# fuzzing probe's F1: a heap overflow in the ellipsoid quadrature that made
# `check` abort with "free(): invalid next size"). The probe's four inputs
# through `shape info` and in one scene through `check` and a short `run`:
# exit 0, and each volume against the Steiner formula for a swept spheroid,
# V = V0 + S r + M r^2 + 4/3 pi r^3 (area S and integrated mean curvature M
# in closed form). tests/unit/shape_flake.c checks the moments as well.
set -u
bin="$1"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_shape_flake.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# steiner A C r: equatorial semi-axis A, polar C (core), swept by r
steiner() {
    awk -v A="$1" -v C="$2" -v r="$3" 'function asin(x) { return atan2(x, sqrt(1 - x * x)) }
    function asinh(x) { return log(x + sqrt(x * x + 1)) }
    BEGIN {
        pi = atan2(0, -1); V0 = 4 / 3 * pi * A * A * C
        if (A > C) { e = sqrt(1 - C * C / (A * A)); S = 2 * pi * A * A + pi * C * C / e * log((1 + e) / (1 - e))
                     M = 2 * pi * (C + A * asin(e) / e) }
        else { e = sqrt(1 - A * A / (C * C)); k = sqrt(C * C - A * A); S = 2 * pi * A * A * (1 + C / (A * e) * asin(e))
               M = 2 * pi * (C + A * A / k * asinh(k / A)) }
        printf "%.12g", V0 + S * r + M * r * r + 4 / 3 * pi * r * r * r }'
}

# semi-axes, option, value, core A, core C, r (A: the two equal axes)
cases=(
    "0.005,0.005,0.0005 --margin 1e-4 0.0049 0.0004 1e-4"
    "0.02,0.001,0.001 --rounding 1e-5 0.001 0.02 1e-5"
    "0.05,0.001,0.001 --rounding 1e-4 0.001 0.05 1e-4"
    "0.02,0.02,0.001 --margin 5e-5 0.01995 0.00095 5e-5"
)
for c in "${cases[@]}"; do
    read -r size opt val A C r <<<"$c"
    out=$("$bin" shape info ellipsoid --size "$size" "$opt" "$val" 2>&1)
    rc=$?
    vol=$(awk '/^volume/ {print $2}' <<<"$out")
    exp=$(steiner "$A" "$C" "$r")
    check "shape info ellipsoid --size $size $opt $val: exit 0 (got $rc), volume $exp m^3 (got $vol, rel tol 1e-9)" \
        "$([[ $rc == 0 ]] && awk -v v="$vol" -v e="$exp" 'BEGIN {print (v > e * (1 - 1e-9) && v < e * (1 + 1e-9))}' || echo 0)"
done

cat >"$tmp/flakes.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
shapes:
  - {name: flake, type: ellipsoid, semi_axes: [0.005, 0.005, 0.0005], margin: 0.0001}
  - {name: needle, type: ellipsoid, semi_axes: [0.02, 0.001, 0.001], rounding: 0.00001}
  - {name: long_needle, type: ellipsoid, semi_axes: [0.05, 0.001, 0.001], rounding: 0.0001}
  - {name: wide_flake, type: ellipsoid, semi_axes: [0.02, 0.02, 0.001], margin: 0.00005}
particles:
  - generator: list
    material: m
    spheres:
      - {position: [0, 0, 0], shape: flake}
      - {position: [0.2, 0, 0], shape: needle}
      - {position: [0.4, 0, 0], shape: long_needle}
      - {position: [0.6, 0, 0], shape: wide_flake}
EOF
out=$(cd "$tmp" && "$bin" check flakes.yaml 2>&1)
rc=$?
check "check on the four flakes and needles: exit 0 (got $rc)" "$([[ $rc == 0 ]] && grep -c '^check: ok' <<<"$out" || echo 0)"
(cd "$tmp" && "$bin" run flakes.yaml -o "$tmp/out" >/dev/null 2>"$tmp/err")
rc=$?
check "run of the four flakes and needles: exit 0 (got $rc), stderr empty" "$([[ $rc == 0 && ! -s $tmp/err ]] && echo 1 || echo 0)"
finish
