#!/usr/bin/env bash
# bad_input.sh — every scene in tests/cli/bad/ is rejected cleanly.
#
# Usage: bash bad_input.sh /path/to/shapedem /path/to/repo
#
# Each bad scene carries its expectation in a comment line:
#     # expect: line N key KEY [file NAME]
# (KEY "-" when the error has no key; NAME when the error names another
# file than the scene, e.g. a CSV file). For each scene, `shapedem run SCENE
# -o TMP/out`, started in a scratch directory, must exit 2, print exactly one
# line to stderr containing the file name, ":N:" and the key, and create no
# output directory; `shapedem check SCENE` must exit 2 with the same place.
set -u

exe=${1:?usage: bad_input.sh SHAPEDEM REPO}
repo=${2:?usage: bad_input.sh SHAPEDEM REPO}
# Absolute paths: the CLI runs in a scratch directory.
[[ $exe == */* ]] && exe=$(cd "$(dirname "$exe")" && pwd)/$(basename "$exe")
repo=$(cd "$repo" && pwd)
bad_dir=$repo/tests/cli/bad

tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_bad_input.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

pass=0
fail=0

report() { # report PASS|FAIL name message
    echo "$1 $2: $3"
    if [[ $1 == PASS ]]; then pass=$((pass + 1)); else fail=$((fail + 1)); fi
}

# Runs the CLI in a fresh scratch directory; sets rc, err (stderr text) and
# nerr (its number of lines).
run_cli() {
    rm -rf "$tmp/work" "$tmp/out"
    mkdir -p "$tmp/work"
    (cd "$tmp/work" && "$exe" "$@" >"$tmp/stdout" 2>"$tmp/stderr")
    rc=$?
    err=$(cat "$tmp/stderr")
    nerr=$(wc -l <"$tmp/stderr")
}

# check_case NAME SCENE LINE KEY FILE: LINE 0 means "no line" (e.g. a scene
# file that is not there), KEY "-" means "no key".
check_case() {
    local name=$1 scene=$2 line=$3 key=$4 file=$5 why=""
    run_cli run "$scene" -o "$tmp/out"
    if [[ $rc -ne 2 ]]; then
        why="run: exit status $rc, expected 2"
    elif [[ $nerr -ne 1 || -z $err ]]; then
        why="run: expected exactly one line on stderr, got $nerr"
    elif [[ $err != *"$file"* ]]; then
        why="run: stderr does not name $file"
    elif [[ $line -gt 0 && $err != *":$line:"* ]]; then
        why="run: stderr does not contain :$line:"
    elif [[ $key != - && $err != *"$key"* ]]; then
        why="run: stderr does not contain the key $key"
    elif [[ -e $tmp/out ]]; then
        why="run: created the output directory"
    elif [[ -n $(ls -A "$tmp/work") ]]; then
        why="run: wrote into the current directory"
    fi
    local run_err=$err
    if [[ -z $why ]]; then
        run_cli check "$scene"
        if [[ $rc -ne 2 ]]; then
            why="check: exit status $rc, expected 2"
        elif [[ $line -gt 0 && $err != *"$file:$line:"* ]]; then
            why="check: stderr does not contain $file:$line:"
        fi
    fi
    if [[ -z $why ]]; then
        report PASS "$name" "$run_err"
    else
        report FAIL "$name" "$why; stderr: $err"
    fi
}

if [[ ! -x $exe ]]; then
    echo "FAIL setup: $exe is not an executable"
    echo "0 passed, 1 failed"
    exit 1
fi

shopt -s nullglob
scenes=("$bad_dir"/*.yaml)
if [[ ${#scenes[@]} -eq 0 ]]; then
    echo "FAIL setup: no bad scenes in $bad_dir"
    echo "0 passed, 1 failed"
    exit 1
fi

for scene in "${scenes[@]}"; do
    name=$(basename "$scene" .yaml)
    expect=$(grep -m1 '^# expect:' "$scene" || true)
    if [[ ! $expect =~ ^#\ expect:\ line\ ([0-9]+)\ key\ ([^[:space:]]+)(\ file\ ([^[:space:]]+))?[[:space:]]*$ ]]; then
        report FAIL "$name" "no '# expect: line N key KEY [file NAME]' line"
        continue
    fi
    line=${BASH_REMATCH[1]}
    key=${BASH_REMATCH[2]}
    file=${BASH_REMATCH[4]:-$(basename "$scene")}
    check_case "$name" "$scene" "$line" "$key" "$file"
done

# A scene file that is not there at all: no line, no key, still exit 2.
check_case "scene-not-found" "$tmp/no-such-scene.yaml" 0 - "no-such-scene.yaml"

echo "$pass passed, $fail failed"
[[ $fail -eq 0 ]]
