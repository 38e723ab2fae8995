# lib.sh — what every validate/cases/*/case.sh shares, sourced at its top
# (the long tier's counterpart of tests/cli/lib.sh):
#   compare LABEL COMPUTED EXPECTED TOL [full]
#                     |computed - expected| <= tol, printed as
#                     "ok|FAIL CASE: LABEL computed X expected Y tol T"
#                     (docs/validation/README.md: the index quotes these
#                     lines); with "full" the check counts only in a full
#                     run (a quick run prints it as "info")
#   claim LABEL 0|1 [full]   a check that is a statement, not a number
#   finish            prints the counts; status 0 only when none failed
# A case script is run as: bash case.sh SHAPEDEM ROOT OUT QUICK DOCS
# (validate/run): OUT its scratch directory, QUICK 1 for the short form,
# DOCS the directory its figures go to (docs/validation in a full run,
# OUT in a quick one).
pass=0
fail=0
case_name=$(basename "$(dirname "${BASH_SOURCE[1]}")")
bin="$1"
root="$2"
out="$3"
quick="$4"
docs="$5"
mkdir -p "$out"
counts() { [[ "${1:-}" != full || "$quick" != 1 ]]; }
compare() {
    local label="$1" c="$2" e="$3" t="$4" ok
    ok=$(awk -v c="$c" -v e="$e" -v t="$t" 'BEGIN { d = c - e; if (d < 0) d = -d; print (c == c && d <= t) ? 1 : 0 }')
    if ! counts "${5:-}"; then
        echo "info $case_name: $label computed $c expected $e tol $t (full run only)"
    elif [[ "$ok" == 1 ]]; then
        pass=$((pass + 1))
        echo "ok   $case_name: $label computed $c expected $e tol $t"
    else
        fail=$((fail + 1))
        echo "FAIL $case_name: $label computed $c expected $e tol $t"
    fi
}
claim() {
    if ! counts "${3:-}"; then
        echo "info $case_name: $1 ($([[ $2 == 1 ]] && echo holds || echo does not hold); full run only)"
    elif [[ "$2" == 1 ]]; then
        pass=$((pass + 1))
        echo "ok   $case_name: $1"
    else
        fail=$((fail + 1))
        echo "FAIL $case_name: $1"
    fi
}
finish() {
    echo "$case_name: $pass passed, $fail failed"
    ((fail == 0))
}
