#!/usr/bin/env bash
# parser_input.sh — the scene reader's limits and encodings (robustness
# probe F6, F7, F10, F11, F12, F13): each bad input is refused with exit 2
# and one stderr line naming the file and the line, and the near misses a
# user writes on purpose are accepted.
#
# Usage: bash parser_input.sh /path/to/shapedem /path/to/repo
set -u
exe=${1:?usage: parser_input.sh SHAPEDEM REPO}
repo=${2:?usage: parser_input.sh SHAPEDEM REPO}
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
repo=$(cd "$repo" && pwd)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_parser_input.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
pass=0
fail=0
report() { # report 1|0 name detail
    if [[ $1 == 1 ]]; then pass=$((pass + 1)); echo "PASS $2: $3"; else fail=$((fail + 1)); echo "FAIL $2: $3"; fi
}

# refused NAME FILE LINE TEXT [ARGS...]: `check FILE` exits 2 with one line
# containing FILE:LINE: and TEXT (LINE 0: no line expected).
refused() {
    local name=$1 file=$2 line=$3 text=$4
    shift 4
    local err rc n
    err=$(timeout 120 "$exe" check "$file" "$@" 2>&1 >/dev/null)
    rc=$?
    n=$(printf '%s\n' "$err" | wc -l)
    local want="$file:$line:"
    [[ $line == 0 ]] && want="$file"
    if [[ $rc == 2 && $n == 1 && $err == *"$want"* && $err == *"$text"* ]]; then
        report 1 "$name" "$err"
    else
        report 0 "$name" "exit $rc (expected 2), $n line(s), expected '$want' and '$text'; got: $err"
    fi
}

# accepted NAME FILE: `check FILE` exits 0.
accepted() {
    local out rc
    out=$("$exe" check "$2" 2>&1)
    rc=$?
    if [[ $rc == 0 ]]; then report 1 "$1" "check exit 0"; else report 0 "$1" "exit $rc, expected 0: $out"; fi
}

head3='simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: glass, density: 2500, youngs_modulus: 1.0e7}]
particles: [{generator: list, material: glass, spheres: [{position: [0, 0, 0.01], radius: 0.001}]}]'

# F7: 100,000 levels of flow nesting took libyaml 95 s; the prescan stops
# at level 65 (the timeout only guards against the old hang).
python3 -c "n = 100000; print('simulation: ' + '[' * n + ']' * n)" >deep-list.yaml
refused "100000 nested lists" deep-list.yaml 1 "nested more than 64 deep"
python3 -c "n = 100000; print('simulation: ' + '{a: ' * n + '1' + '}' * n)" >deep-map.yaml
refused "100000 nested mappings" deep-map.yaml 1 "nested more than 64 deep"
{ printf '%s\nwalls:\n' "$head3"; for ((k = 0; k < 1000; ++k)); do printf -- '- '; done; printf 'x\n'; } >deep-block.yaml
refused "1000 nested block lists" deep-block.yaml 5 "nested more than 64 deep"

# F11: the five libyaml reader errors, each on line 5 of its file.
n=0
for bytes in '\xb5' '\xc3\x28' '\xed\xa0\x80' '\x01' '\xe9'; do
    n=$((n + 1))
    { printf '%s\n\n' "$head3"; printf '# radius in '; printf "$bytes"; [[ $bytes != '\xe9' ]] && printf 'm\n'; } >bytes$n.yaml
done
refused "invalid leading UTF-8 octet" bytes1.yaml 5 "invalid leading UTF-8 octet (byte 0xB5)"
refused "invalid trailing UTF-8 octet" bytes2.yaml 5 "invalid trailing UTF-8 octet"
refused "invalid Unicode character" bytes3.yaml 5 "invalid Unicode character (U+D800)"
refused "control character" bytes4.yaml 5 "control characters are not allowed (U+0001)"
refused "incomplete UTF-8 sequence at the end" bytes5.yaml 5 "incomplete UTF-8 octet sequence"

# F6: a '...' with nothing after it, or a leading '---', is one document.
printf '%s\n...\n# the end\n' "$head3" >dots-end.yaml
accepted "'...' then only a comment" dots-end.yaml
printf -- '---\n%s\n' "$head3" >leading-dashes.yaml
accepted "a leading '---'" leading-dashes.yaml
printf '%s\n...\n---\nwalls: []\n' "$head3" >dots-dashes.yaml
refused "'...' then '---' and a second document" dots-dashes.yaml 5 "second YAML document"

# F13: an explicit numeric tag makes a quoted number a number; a string tag
# makes a plain number a string.
sed 's/dt: 1.0e-6/dt: !!float "1.0e-6"/' <<<"$head3" >float-tag.yaml
accepted '!!float "1.0e-6"' float-tag.yaml
sed 's/dt: 1.0e-6/dt: !str 1.0e-6/' <<<"$head3" >custom-tag.yaml
refused "a custom tag is not a number" custom-tag.yaml 1 "simulation.dt: expected a number"
sed 's/density: 2500/density: "\\e[31m2500\\r"/' <<<"$head3" >escape.yaml
refused "a quoted terminal escape is echoed escaped" escape.yaml 2 'got "\x1b[31m2500\r"'
if grep -q $'\e' <<<"$("$exe" check escape.yaml 2>&1)"; then
    report 0 "no raw ESC byte on stderr" "an ESC byte reached stderr"
else
    report 1 "no raw ESC byte on stderr" "none"
fi

# F12: --threads is bounded like simulation.threads.
err=$("$exe" check dots-end.yaml --threads 5000 2>&1 >/dev/null)
rc=$?
report "$([[ $rc == 2 && $err == *--threads*1024* ]] && echo 1 || echo 0)" "--threads 5000" "exit $rc: $err"
out=$("$exe" check dots-end.yaml --threads 1024 2>&1)
report "$([[ $? == 0 && $out == *"threads      1024"* ]] && echo 1 || echo 0)" "--threads 1024 accepted" \
    "$(grep '^threads' <<<"$out")"

# F10: particle counts and memory are checked before anything is built.
# Two aliased generators of 1e9 spheres: refused at the first generator
# that does not fit (the memory of 1e9 spheres, about 596 GiB, or the 1e9
# total on a machine that has it), with its line and key.
cat >alias.yaml <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: m, density: 2500, youngs_modulus: 1.0e7}]
particles:
  - &g {generator: lattice, material: m, radius: 0.001, origin: [0, 0, 0], spacing: 0.0022, count: [1000, 1000, 1000]}
  - *g
EOF
err=$("$exe" check alias.yaml 2>&1 >/dev/null)
rc=$?
ok=0
[[ $rc == 2 && ( $err == *alias.yaml:4:\ particles\[0\].count:* || $err == *alias.yaml:5:\ particles\[1\].count:* ) &&
   $err == *"particles up to here"* ]] && ok=1
report $ok "two aliased 1e9-sphere generators" "exit $rc: $err"
# The probe's one-digit slip, count: [20, 20, 100000] (4e7 spheres, about
# 24 GiB), under a 2 GiB address-space limit. Not under a sanitizer, whose
# shadow memory needs the address space (and on a large machine the scene
# would be built).
sed 's/count: \[20, 20, 20\]/count: [20, 20, 100000]/' "$repo/bench/scenes/spheres-settle-8000.yaml" >typo.yaml
if grep -qa __asan_init "$exe"; then
    echo "SKIP count typo under ulimit -v: a sanitizer build"
else
    err=$( (ulimit -v 2097152 && "$exe" check typo.yaml) 2>&1 >/dev/null)
    rc=$?
    ok=0
    line=$(grep -n 'count: \[20, 20, 100000\]' typo.yaml | cut -d: -f1)
    [[ $rc == 2 && $err == *typo.yaml:$line:\ particles\[0\].count:*40000000\ particles*GiB*ulimit\ -v* ]] && ok=1
    report $ok "count typo 4e7 spheres under a 2 GiB limit" "exit $rc: $err"
fi

echo "$pass passed, $fail failed"
[[ $fail == 0 ]]
