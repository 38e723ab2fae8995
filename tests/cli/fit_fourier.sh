#!/usr/bin/env bash
# fit_fourier.sh — `shapedem shape fit-fourier` (seed 002 §2.3, §3.1):
#   - a sampled circle (made here, centre (1, 2), R = 0.02 m) gives
#     a0 = 2R, a_n = b_n = 0, coverage ~100 %, no reduction;
#   - the rock-like fixture (tests/cli/outlines/rock.csv, header and
#     comments) fits, needs the reduction, and covers > 95 %; its printed
#     scene entry has N + 1 values of fourier_a and N of fourier_b, and a 2D
#     scene made with it passes `shapedem check`;
#   - bad outlines and options: exit 2, one line on stderr naming the file
#     and line (bad row) or the option, nothing on stdout.
# Usage: bash fit_fourier.sh SHAPEDEM REPO
set -u
bin="$1"
root="$2"
dir="$root/tests/cli/outlines"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_fit_fourier.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
near() { # near VALUE EXPECTED TOL -> 1 if |VALUE - EXPECTED| <= TOL
    awk -v v="$1" -v e="$2" -v t="$3" 'BEGIN { d = v - e; if (d < 0) d = -d; print (v != "" && d <= t) ? 1 : 0 }'
}

# ---- a sampled circle ---------------------------------------------------------
awk 'BEGIN { pi = atan2(0, -1); for (i = 0; i < 720; ++i) printf "%.12f,%.12f\n", 1 + 0.02 * cos(2 * pi * i / 720), 2 + 0.02 * sin(2 * pi * i / 720) }' >"$tmp/circle.csv"
out=$("$bin" shape fit-fourier "$tmp/circle.csv" --order 6 2>"$tmp/err")
rc=$?
check "circle: exit 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
a0=$(awk '$1 == "0" && NF == 3 {print $2}' <<<"$out")
check "circle: a0 = 2R = 0.04 m (got $a0, tol 1e-6)" "$(near "$a0" 0.04 1e-6)"
maxc=$(awk '$1 ~ /^[1-6]$/ && NF == 3 { for (k = 2; k <= 3; ++k) { v = $k < 0 ? -$k : $k; if (v > m) m = v } } END { printf "%.3g", m + 0 }' <<<"$out")
check "circle: |a_n|, |b_n| <= 1e-7 m for n >= 1 (got $maxc)" "$(awk -v v="$maxc" 'BEGIN {print (v <= 1e-7)}')"
ox=$(awk '/^origin/ {gsub(/[(,]/, " "); print $2}' <<<"$out")
check "circle: origin x = 1 (got $ox)" "$(near "$ox" 1 1e-9)"
check "circle: no reduction" "$(grep -q '^reduction *not needed' <<<"$out" && echo 1 || echo 0)"
cov=$(awk '/^coverage/ {print $2}' <<<"$out")
check "circle: coverage > 99.99 % (got $cov)" "$(awk -v v="$cov" 'BEGIN {print (v > 99.99)}')"

# ---- the rock-like fixture --------------------------------------------------------
out=$("$bin" shape fit-fourier "$dir/rock.csv" --order 8 2>"$tmp/err")
rc=$?
check "rock: exit 0 (got $rc; $(head -c 200 "$tmp/err"))" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
check "rock: 120 points read (header and comments skipped, closing point dropped)" \
    "$(grep -q '^outline .*: 120 points' <<<"$out" && echo 1 || echo 0)"
check "rock: reduction needed and reported" "$(grep -q '^reduction *needed: [1-9][0-9]* step' <<<"$out" && echo 1 || echo 0)"
cov=$(awk '/^coverage/ {print $2}' <<<"$out")
check "rock: coverage > 95 % (got $cov)" "$(awk -v v="$cov" 'BEGIN {print (v > 95 && v <= 100)}')"
rho=$(awk '/^convexity/ {print $(NF - 3)}' <<<"$out")
check "rock: min p + p'' >= 0 after reduction (got $rho)" "$(awk -v v="$rho" 'BEGIN {print (v >= 0)}')"
na=$(awk -F'[][]' '/fourier_a:/ {print split($2, x, ",")}' <<<"$out")
nb=$(awk -F'[][]' '/fourier_b:/ {print split($2, x, ",")}' <<<"$out")
check "rock: scene entry with 9 fourier_a and 8 fourier_b values (got $na, $nb)" \
    "$([[ $na == 9 && $nb == 8 ]] && echo 1 || echo 0)"

# the printed entry, pasted into a 2D scene, is accepted (convex to the
# printed precision) and gives the particle
{
    printf 'simulation:\n  dimension: 2\n  dt: 1.0e-5\n  duration: 0.001\n  gravity: [0, -9.8, 0]\n'
    printf 'materials:\n  - name: grain\n    density: 2700\n    youngs_modulus: 1.0e7\nshapes:\n'
    sed -n '/- name: fitted/,$p' <<<"$out"
    printf 'particles:\n  - generator: list\n    material: grain\n    spheres:\n'
    printf '      - {position: [0.5, 0.5, 0], shape: fitted}\n'
} >"$tmp/fitted.yaml"
"$bin" check "$tmp/fitted.yaml" >"$tmp/check.out" 2>"$tmp/err"
rc=$?
check "rock: the printed scene entry passes 'shapedem check' (rc $rc; $(head -c 200 "$tmp/err"))" \
    "$([[ $rc == 0 ]] && grep -q '^particles *1:' "$tmp/check.out" && echo 1 || echo 0)"

# ---- bad input: exit 2, one line on stderr, nothing on stdout ---------------------------
bad() { # bad NAME EXPECTED-TEXT ARGS...
    local name=$1 want=$2
    shift 2
    "$bin" shape fit-fourier "$@" >"$tmp/out" 2>"$tmp/err"
    local rc=$? nerr nout
    nerr=$(wc -l <"$tmp/err")
    nout=$(wc -c <"$tmp/out")
    local ok=0
    [[ $rc == 2 && $nerr == 1 && $nout == 0 ]] && grep -qF -- "$want" "$tmp/err" && ok=1
    check "$name: exit 2, one line with '$want' (rc $rc: $(head -c 200 "$tmp/err"))" "$ok"
}
bad "bad row" "bad-row.csv:6:" "$dir/bad-row.csv"
bad "missing file" "no-such-outline.csv" "$dir/no-such-outline.csv"
bad "two points" "two-points.csv" "$dir/two-points.csv"
bad "collinear" "collinear.csv" "$dir/collinear.csv"
bad "not finite" "not-finite.csv:3:" "$dir/not-finite.csv"
bad "order not a number" "--order" "$dir/rock.csv" --order abc
bad "order too high" "--order" "$dir/rock.csv" --order 400
bad "beta out of range" "--beta" "$dir/rock.csv" --beta 1.5
bad "too few directions" "--directions" "$dir/rock.csv" --order 8 --directions 10
bad "unknown option" "--frobnicate" "$dir/rock.csv" --frobnicate 1
"$bin" shape fit-fourier >/dev/null 2>&1
rc=$?
check "no outline: usage, exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"

finish
