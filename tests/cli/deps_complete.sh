#!/usr/bin/env bash
# deps_complete.sh — scripts/deps.sh installs everything the project uses:
# every Python module a tracked script imports and every command a test
# script or a README command calls comes from a Debian package that deps.sh
# lists (or one of their dependencies, or a package every Debian system has).
# tests/tools/deps_check.py does the finding; this test also shows that it
# catches a package dropped from the list, so the check itself cannot rot.
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
py=/usr/bin/python3  # Debian's interpreter: the one deps.sh installs modules for
if [[ ! -x $py ]]; then
    echo "FAIL $py is missing: scripts/deps.sh installs the Debian package python3"
    exit 1
fi
"$py" "$root/tests/tools/deps_check.py" "$root"
check "every module and command comes from a package scripts/deps.sh installs" "$(($? == 0))"

# The check must fail when a package is removed from the list, naming the
# package that provides what is then missing: matplotlib itself, and make,
# which build-essential brings.
for case in python3-matplotlib:python3-matplotlib build-essential:make; do
    pkg=${case%%:*} want=${case#*:}
    out=$("$py" "$root/tests/tools/deps_check.py" "$root" --without "$pkg" 2>&1)
    rc=$?
    named=$(grep -c "^FAIL .*Debian package $want," <<<"$out")
    grep "^FAIL" <<<"$out" | head -3
    check "without $pkg: the check fails (rc $rc) and names $want ($named line(s))" \
        "$([[ $rc == 1 && $named -ge 1 ]] && echo 1 || echo 0)"
done

# The README shows the list (the line after its marker, which `make docs`
# writes): it must be scripts/deps.sh --list, in order; a README that drops
# or adds a package fails, shown on a copy with one package dropped.
readme_list() { sed -n '/^<!-- scripts\/deps.sh --list -->$/{n;p;q;}' "$1" | tr -d '`'; }
want=$(SHAPEDEM_WITH_BENCH= bash "$root/scripts/deps.sh" --list | paste -sd ' ')
got=$(readme_list "$root/README.md")
[[ $got == "$want" ]] || printf 'README.md lists: %s\nscripts/deps.sh: %s\n(make docs rewrites the README line)\n' "$got" "$want"
check "README.md lists the packages of scripts/deps.sh --list ($(wc -w <<<"$want") packages)" \
    "$([[ -n $want && $got == "$want" ]] && echo 1 || echo 0)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
sed '/^<!-- scripts\/deps.sh --list -->$/{n;s/ python3-h5py//;}' "$root/README.md" >"$tmp/README.md"
got=$(readme_list "$tmp/README.md")
check "a README without python3-h5py in its list is told apart" "$([[ $got != "$want" ]] && echo 1 || echo 0)"
finish
