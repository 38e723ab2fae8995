#!/usr/bin/env bash
# validation_index.sh — docs/validation/README.md, the validation index,
# lists every validation there is:
#  - every program of tests/validation/ (ctest validation.NAME) and every
#    case of validate/cases/ (`make validate`) has a row naming it;
#  - every test a row names exists (validation.NAME, unit.NAME: a C file;
#    cli.NAME: a script; validate: NAME: a case directory with case.sh);
#  - no row keeps a placeholder for its measured value or time;
#  - validate/run refuses an unknown case with one message and exit 2,
#    running nothing.
# Usage: bash validation_index.sh SHAPEDEM REPO
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"
index="$root/docs/validation/README.md"
check "the index exists" "$(yes01 test -s "$index")"
rows=$(grep '^| ' "$index")
for f in "$root"/tests/validation/*.c; do
    n=$(basename "$f" .c)
    check "validation.$n has a row" "$(grep -qE "(^|[ ,])validation\.$n([ ,]|$)" <<<"$(cut -d'|' -f7 <<<"$rows")" && echo 1 || echo 0)"
done
for d in "$root"/validate/cases/*/; do
    n=$(basename "$d")
    check "validate: $n has a row" "$(grep -qF "validate: $n |" <<<"$rows" && echo 1 || echo 0)"
done
# every test named in a row's test column exists
named=$(awk -F'|' 'NF >= 9 {print $7}' <<<"$rows" | tr ',' '\n' | sed 's/^ *//; s/ *$//' | grep -E '^(validation|unit|cli)\.|^validate: ' | sort -u)
while read -r t; do
    [[ -z "$t" ]] && continue
    case "$t" in
        validation.*) f="$root/tests/validation/${t#validation.}.c" ;;
        unit.*) f="$root/tests/unit/${t#unit.}.c" ;;
        cli.*) f="$root/tests/cli/${t#cli.}.sh" ;;
        validate:*) f="$root/validate/cases/${t#validate: }/case.sh" ;;
    esac
    check "row's test $t exists" "$(yes01 test -f "$f")"
done <<<"$named"
check "rows name tests at all ($(wc -l <<<"$named"))" "$([[ $(wc -l <<<"$named") -ge 30 ]] && echo 1 || echo 0)"
left=$(grep -cE '\| (MEASURED|TIME) \|' "$index")
check "no placeholder left in a row ($left)" "$([[ $left == 0 ]] && echo 1 || echo 0)"
# validate/run: an unknown case is refused before anything runs
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
err=$(bash "$root/validate/run" "$(dirname "$bin")" no_such_case 2>&1 >"$tmp/out")
rc=$?
check "validate/run: unknown case, exit 2 (got $rc)" "$([[ $rc == 2 ]] && echo 1 || echo 0)"
check "validate/run: one line naming the case" \
    "$([[ $(wc -l <<<"$err") == 1 ]] && grep -q "no case 'no_such_case'" <<<"$err" && echo 1 || echo 0)"
check "validate/run: nothing run" "$([[ ! -s "$tmp/out" ]] && echo 1 || echo 0)"
finish validation_index
