#!/usr/bin/env bash
# docs_help_width.sh — the help text reads in a terminal and the docs stand
# on their own:
#  - no line of any help or usage text is over 120 columns (counted in bytes,
#    which is stricter than characters for the few non-ASCII signs);
#  - docs/scene-format.md is a valid markdown table: every row has the
#    header's six cells (a '|' inside a meaning must be escaped);
#  - no tracked doc, example, bench page or help text points to files that
#    are not in the repository (DESIGN.md, STYLE.md, the papers' "seeds/" or
#    "seed 00N" by file), and every paper cited by short name, such as
#    [Naderi 2024], is listed in docs/references.md.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Every help text: the usage (with and without an error), help, help scene,
# and the usage of each sub-command. stderr is kept: usage errors go there.
topics=("" "--help" "-h" "help" "help scene" "shape" "shape info" "shape fit-fourier" "run" "check")
for t in "${topics[@]}"; do
    name="shapedem${t:+ $t}"
    # shellcheck disable=SC2086
    "$bin" $t >"$tmp/out" 2>&1
    rc=$?
    lines=$(wc -l <"$tmp/out")
    long=$(awk 'length($0) > m {m = length($0)} END {print m + 0}' "$tmp/out")
    over=$(awk 'length($0) > 120' "$tmp/out" | wc -l)
    # exit 0 for help, 2 for a usage error; anything else is a crash
    check "'$name': exit $rc, $lines lines, longest $long columns (at most 120), $over over" \
        "$([[ ($rc == 0 || $rc == 2) && $lines -gt 0 && $over == 0 ]] && echo 1 || echo 0)"
    awk -v n="$name" 'length($0) > 120 {printf "  %s: line %d, %d columns: %.100s...\n", n, NR, length($0), $0}' \
        "$tmp/out" | head -5
done

# A help topic that does not exist is a usage error (one line, exit 2), not the usage.
err=$("$bin" help scnee 2>&1 >/dev/null)
rc=$?
check "'help scnee': exit $rc (2), one line naming the topic" \
    "$([[ $rc == 2 && $(wc -l <<<"$err") == 1 && $err == *"'scnee'"* ]] && echo 1 || echo 0)"

# help scene lists every key: the plain form keeps the key table's rows
# (one row per key in the markdown form).
"$bin" help scene >"$tmp/plain"
"$bin" help scene --markdown >"$tmp/md"
rows=$(grep -c '^| [^-]' "$tmp/md")
keys=$(awk '/^\| [^-]/ && NR > 1 {split($0, c, "`"); print c[2]}' "$tmp/md" | sort -u)
missing=0
for k in $keys; do
    grep -q "^  $k " "$tmp/plain" || grep -q "^  $k\$" "$tmp/plain" || {
        missing=$((missing + 1))
        echo "  key $k has no row in 'help scene'"
    }
done
check "'help scene' has a row for each of the $(wc -w <<<"$keys") keys of the markdown table ($missing missing)" \
    "$([[ $missing == 0 && -n $keys ]] && echo 1 || echo 0)"

# Markdown table: count the cell separators, not escaped ones (\|).
bad=$(awk '/^\|/ {s = $0; gsub(/\\\|/, "", s); n = gsub(/\|/, "", s); if (n != 7) {c++; if (c <= 3) printf "  line %d: %d cells\n", NR, n - 1 > "/dev/stderr"}} END {print c + 0}' "$tmp/md")
check "help scene --markdown: all $rows table rows have 6 cells ($bad do not)" "$([[ $bad == 0 && $rows -gt 1 ]] && echo 1 || echo 0)"
check "docs/scene-format.md is the output of 'help scene --markdown'" \
    "$(cmp -s "$tmp/md" "$root/docs/scene-format.md" && echo 1 || echo 0)"

# The user-facing files: tracked ones when this is a git checkout, else the
# same globs.
if files=$(git -C "$root" ls-files -- 'docs/*.md' README.md 'examples/*' 'bench/*.md' 'bench/scenes/*' 2>/dev/null) &&
    [[ -n $files ]]; then
    :
else
    files=$(cd "$root" && ls -d docs/*.md README.md examples/* bench/*.md bench/scenes/* 2>/dev/null)
fi
for t in "${topics[@]}"; do
    # shellcheck disable=SC2086
    "$bin" $t >>"$tmp/help" 2>&1
done
cat "$tmp/md" >>"$tmp/help"
pat='DESIGN\.md|STYLE\.md|seeds/|[Ss]eed 00[0-9]|00[0-9]_\*'
hits=0
for f in $files; do
    [[ -f "$root/$f" ]] || continue
    n=$(grep -c -E "$pat" "$root/$f")
    if [[ $n != 0 ]]; then
        hits=$((hits + n))
        grep -n -E "$pat" "$root/$f" | head -3 | sed "s|^|  $f:|"
    fi
done
check "$(wc -w <<<"$files") docs, examples and bench files cite no file outside the repository ($hits lines do)" \
    "$([[ $hits == 0 ]] && echo 1 || echo 0)"
n=$(grep -c -E "$pat" "$tmp/help")
grep -E "$pat" "$tmp/help" | head -3 | sed 's|^|  help: |'
check "the help texts cite no file outside the repository ($n lines do)" "$([[ $n == 0 ]] && echo 1 || echo 0)"

# Every short name cited is a row of docs/references.md.
refs="$root/docs/references.md"
cited=$( (for f in $files; do [[ -f "$root/$f" ]] && cat "$root/$f"; done; cat "$tmp/help") |
    grep -o -E '\[[A-Z][A-Za-z-]+ ([0-9]{4}|n\.d\.)\]' | sort -u)
unknown=0
while read -r c; do
    [[ -z $c ]] && continue
    grep -q -F "| $c |" "$refs" || {
        unknown=$((unknown + 1))
        echo "  $c is cited but not listed in docs/references.md"
    }
done <<<"$cited"
check "the $(grep -c . <<<"$cited") papers cited by short name are all in docs/references.md ($unknown are not)" \
    "$([[ -f $refs && $unknown == 0 && -n $cited ]] && echo 1 || echo 0)"

finish
