#!/usr/bin/env bash
# examples_run.sh — every shipped scene still works: each examples/*.yaml and
# bench/scenes/*.yaml passes `shapedem check` (exit 0; warnings allowed, the
# examples say why) and a shortened run (`run --steps N`, the scene's own
# settings otherwise) exits 0 with summary.txt written, and no NaN or inf in
# stats.csv; the examples also write stats.csv and frames.pvd (the bench
# scenes ask for no files). The long forms of these runs live
# in the examples and bench/; this keeps none of them from rotting unseen.
set -u
bin="$1"
root="$2"
steps=${SD_EXAMPLE_STEPS:-40}
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
shopt -s nullglob
scenes=("$root"/examples/*.yaml "$root"/bench/scenes/*.yaml)
check "found the shipped scenes (${#scenes[@]})" "$((${#scenes[@]} >= 6))"
for scene in "${scenes[@]}"; do
    name=${scene#"$root"/}
    "$bin" check "$scene" >"$tmp/check.out" 2>&1
    rc=$?
    check "$name: check exits 0 (got $rc)" "$((rc == 0))"
    ((rc == 0)) || head -3 "$tmp/check.out"
    out="$tmp/out-$(basename "$scene" .yaml)"
    "$bin" run "$scene" --steps "$steps" --threads 2 --quiet -o "$out" >"$tmp/run.out" 2>&1
    rc=$?
    check "$name: a $steps-step run exits 0 (got $rc)" "$((rc == 0))"
    ((rc == 0)) || head -3 "$tmp/run.out"
    want=(summary.txt)
    [[ $name == examples/* ]] && want+=(stats.csv frames.pvd)
    for f in "${want[@]}"; do
        check "$name: wrote $f" "$([[ -s $out/$f ]] && echo 1 || echo 0)"
    done
    if [[ -f $out/stats.csv ]]; then
        check "$name: no nan or inf in stats.csv" \
            "$(! grep -qiE '(^|,)-?(nan|inf)(,|$)' "$out/stats.csv" && echo 1 || echo 0)"
    fi
    rm -rf "$out"
done
finish
