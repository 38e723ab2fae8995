#!/usr/bin/env bash
# gpu_run_cpu_path.sh — bench/gpu/run's CPU reference path (issue 13), so
# the script and its comparison are tested where no GPU is: `bench/gpu/run
# --quick --cpu` on the build under test (no build of its own) runs every
# equality scene of bench/gpu/scenes 400 steps on 1 and on 2 threads and
# compares the last checkpoints with sd_ckpt_diff; the test asserts that it
# exits 0, that every scene has its row and compares identical, that the
# math_bits C and C++ builds agree, and that every benchmark scene was
# generated, passed `shapedem check` and ran. Then the tool itself: two
# checkpoints of the same scene 100 steps apart must be reported different
# (exit 1); unit.ckpt_diff checks a 1-ulp difference.
set -u
bin="$1"
src="$2"
build=$(cd "$(dirname "$bin")" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [[ ! -x "$build/tests/sd_ckpt_diff" ]]; then
    echo "FAIL: $build/tests/sd_ckpt_diff is not built (the tests' targets build it)"
    exit 1
fi
bash "$src/bench/gpu/run" --quick --cpu --build "$build" --no-build --out "$tmp/out" >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
cat "$tmp/stdout"
check "bench/gpu/run --quick --cpu exits 0 (got $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
check "it says it runs the CPU reference path" "$(grep -q 'CPU reference path' "$tmp/stdout" && echo 1 || echo 0)"
check "the table is written" "$([[ -s "$tmp/out/gpu-run.md" ]] && echo 1 || echo 0)"
nscenes=0
for f in "$src"/bench/gpu/scenes/*.yaml; do
    c=$(basename "$f" .yaml)
    nscenes=$((nscenes + 1))
    line=$(grep "^| $c | " "$tmp/stdout" | head -1)
    check "$c: 1 vs 2 threads compared identical ($line)" "$([[ "$line" == *"| identical |"* ]] && echo 1 || echo 0)"
done
check "$nscenes equality scenes (at least the 8 kinds)" "$([[ $nscenes -ge 8 ]] && echo 1 || echo 0)"
check "math_bits: the C and C++ builds agree" "$(grep -q '^| math bits .*| identical (digest' "$tmp/stdout" && echo 1 || echo 0)"
nb=$(grep -cE '^\| (spheres-settle|polyhedra-settle|grid-pour|convex-settle|planar-packing) \| [0-9]+ \| 5 \| [0-9.e+]+ \|' "$tmp/stdout")
check "5 benchmark scenes generated, checked and run ($nb)" "$([[ $nb == 5 ]] && echo 1 || echo 0)"

# the tool tells two different states apart (the same scene at steps 100 and 200)
a="$tmp/out/eq-spheres-ref"
"$bin" run "$src/bench/gpu/scenes/spheres.yaml" --steps 200 --threads 2 -o "$tmp/two" --quiet >/dev/null 2>&1
"$build/tests/sd_ckpt_diff" "$tmp/two/checkpoint-000100.h5" "$tmp/two/checkpoint-000200.h5" >"$tmp/d1" 2>&1
rc=$?
check "sd_ckpt_diff: states 100 steps apart differ (exit $rc, $(tail -1 "$tmp/d1"))" "$([[ $rc == 1 ]] && grep -q DIFFERENT "$tmp/d1" && echo 1 || echo 0)"
"$build/tests/sd_ckpt_diff" "$a/checkpoint-000100.h5" "$tmp/two/checkpoint-000100.h5" >"$tmp/d2" 2>&1
rc=$?
check "sd_ckpt_diff: the same step of another run on 2 threads is identical (exit $rc)" "$([[ $rc == 0 ]] && echo 1 || echo 0)"
"$build/tests/sd_ckpt_diff" "$a/checkpoint-000100.h5" "$tmp/none.h5" >"$tmp/d3" 2>&1
rc=$?
check "sd_ckpt_diff: a missing file is exit 2 with the reason ($(head -1 "$tmp/d3"))" "$([[ $rc == 2 ]] && grep -q 'none.h5' "$tmp/d3" && echo 1 || echo 0)"
finish
