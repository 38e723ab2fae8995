#!/usr/bin/env bash
# shape_info.sh — `shapedem shape info` prints a shape's mass properties:
# a box's volume and principal moments against closed forms, a scene's
# shapes, and exit status 2 for an unknown kind.
set -u
bin="$1"
root="$2"
pass=0
fail=0
check() {
    if [[ "$2" == 1 ]]; then pass=$((pass + 1)); echo "PASS $1"; else fail=$((fail + 1)); echo "FAIL $1"; fi
}
out=$("$bin" shape info box --size 0.01,0.02,0.03 --density 2500)
vol=$(awk '/^volume/ {print $2}' <<<"$out")
mom=$(awk '/^principal moments/ {print $3}' <<<"$out" | tr -d '(,')
check "box volume 6e-06 m^3 (got $vol)" "$(awk -v v="$vol" 'BEGIN {print (v > 5.999999e-6 && v < 6.000001e-6)}')"
# I_x / rho = V (b^2 + c^2) / 12 = 6.5e-10 m^5
check "box moment about x 6.5e-10 m^5 (got $mom)" "$(awk -v v="$mom" 'BEGIN {print (v > 6.499999e-10 && v < 6.500001e-10)}')"
out=$("$bin" shape info "$root/tests/validation/scenes/mixed-packing.yaml")
check "scene shapes listed (5)" "$([[ $(grep -c '^shape ' <<<"$out") == 5 ]] && echo 1 || echo 0)"
"$bin" shape info blob --size 1 >/dev/null 2>&1
rc=$?
check "unknown kind exits 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
