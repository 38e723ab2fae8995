#!/usr/bin/env bash
# backend_cuda_no_device.sh — the backend choice (simulation.backend,
# --backend; world/backend.c):
#  - `backend: cuda` (the scene key, then the flag) where no GPU is usable
#    exits 2 before any output: one line on stderr naming the scene and the
#    backend: key's own line (or, for the flag, the option --backend cuda)
#    and the reason (not compiled with CUDA, no CUDA
#    device, driver too old), and no output directory;
#  - `--backend cpu` runs and summary.txt says "backend: cpu (asked for)";
#  - `auto` runs and summary.txt names the backend it chose and why;
#  - a wrong name is a usage error (exit 2).
# On a machine where CUDA runs, the refusal cases are skipped (said so).
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1 [DETAIL], finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_backend.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# A small scene: 8 spheres falling onto a plane, 20 steps.
cat >"$tmp/drop.yaml" <<'YAML'
simulation:
  dt: 1.0e-5
  steps: 20
materials:
  - {name: glass, density: 2500, youngs_modulus: 1.0e7, poisson_ratio: 0.3, restitution: 0.5, friction: 0.5}
particles:
  - {generator: lattice, material: glass, count: [2, 2, 2], spacing: 0.004, origin: [0, 0, 0.01], radius: 0.0015}
walls:
  - {type: plane, point: [0, 0, 0], normal: [0, 0, 1], material: glass}
YAML
sed 's/^  steps: 20$/  steps: 20\n  backend: cuda/' "$tmp/drop.yaml" >"$tmp/drop-cuda.yaml"

cd "$tmp" || exit 1
"$bin" run drop.yaml --backend cpu -o out-cpu >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
check "--backend cpu runs" "$([[ $rc == 0 ]] && echo 1)" "exit $rc: $(cat "$tmp/stderr")"
line=$(grep '^backend:' out-cpu/summary.txt 2>/dev/null)
check "summary.txt: backend: cpu (asked for)" "$([[ $line == 'backend: cpu (asked for)' ]] && echo 1)" "got '$line'"

"$bin" run drop.yaml -o out-auto >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
check "backend auto runs" "$([[ $rc == 0 ]] && echo 1)" "exit $rc: $(cat "$tmp/stderr")"
auto=$(grep '^backend:' out-auto/summary.txt 2>/dev/null)
check "summary.txt names auto's choice and why" \
    "$([[ $auto =~ ^backend:\ (cpu|cuda)\ \(.+\)$ ]] && echo 1)" "got '$auto'"
echo "auto chose: $auto"

"$bin" run drop.yaml --backend gpu -o out-bad >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
check "--backend gpu is a usage error" "$([[ $rc == 2 && ! -e out-bad ]] && grep -q 'auto, cpu or cuda' "$tmp/stderr" && echo 1)" \
    "exit $rc: $(cat "$tmp/stderr")"

if [[ $auto == "backend: cuda "* ]]; then
    echo "SKIP the refusals: a CUDA device is usable here ($auto)"
else
    for how in "scene key" "flag"; do
        rm -rf out-cuda
        if [[ $how == "flag" ]]; then
            "$bin" run drop.yaml --backend cuda -o out-cuda >"$tmp/stdout" 2>"$tmp/stderr"
        else
            "$bin" run drop-cuda.yaml -o out-cuda >"$tmp/stdout" 2>"$tmp/stderr"
        fi
        rc=$?
        msg=$(cat "$tmp/stderr")
        nl=$(wc -l <"$tmp/stderr")
        echo "  $how: exit $rc: $msg"
        check "$how: backend cuda without a device exits 2" "$([[ $rc == 2 ]] && echo 1)" "exit $rc"
        # the scene key: its own line (not the simulation: line above it);
        # the flag: the option, and no scene line blamed for it (issue 31)
        if [[ $how == "flag" ]]; then
            check "$how: one line naming the option --backend cuda, not the scene" \
                "$([[ $nl == 1 && $msg == *--backend\ cuda* && $msg != *.yaml:* ]] && echo 1)" "$msg"
        else
            key_line=$(grep -n '^  backend: cuda$' drop-cuda.yaml | cut -d: -f1)
            check "$how: one line naming the file, the backend: line ($key_line) and simulation.backend" \
                "$([[ $nl == 1 && $msg == *drop-cuda.yaml:$key_line:* && $msg == *simulation.backend* ]] && echo 1)" "$msg"
        fi
        check "$how: the reason" \
            "$([[ $msg =~ (not\ compiled\ with\ CUDA|no\ CUDA\ device|driver\ too\ old) ]] && echo 1)" "$msg"
        check "$how: no output directory" "$([[ ! -e out-cuda ]] && echo 1)" "out-cuda exists"
    done
    "$bin" check drop.yaml --backend cuda >"$tmp/stdout" 2>"$tmp/stderr"
    rc=$?
    check "check --backend cuda exits 2 too" "$([[ $rc == 2 ]] && echo 1)" "exit $rc"
fi

finish
