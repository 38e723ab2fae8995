#!/usr/bin/env bash
# readme_commands.sh — every command in README.md runs on this build as
# printed (issue 31). The README's command blocks (lines indented four
# spaces outside ``` fences) are read in order; a block of C (lines ending
# in ; { or }) or the layout listing (first word a directory) is not a
# command block; any other line must start with a command this test knows
# (bash, build/shapedem, python3, PYTHONPATH=build/python python3, mpirun,
# cc, cmake, make, bench/run), so a
# new README line cannot slip past it. They run in a temporary directory
# with copies of examples/ and scripts/ (the analysis scripts write their
# pictures into ../docs/examples/ beside themselves: here an empty folder,
# never the tree's), links to tests/ and bench/, and build/ this build (the
# shapedem binary's directory), with
# Debian's python3 first on PATH and HOME in the temporary directory (the
# install line's ~/.local), the README's PKG_CONFIG_PATH and
# LD_LIBRARY_PATH for it set as it says. Shortened by one knob:
# README_STEPS (default 40) steps, inserted as `--steps N` after each
# `shapedem run SCENE` (README_STEPS=full runs them whole: hours); the
# README text itself is never changed. How each kind is taken:
#   - shapedem, python3, cc, mpirun, bash and cmake --install lines: run,
#     exit status 0; `mpirun` only where it is installed (Open MPI);
#   - `make demo`: its recipe (make -n, with this build as BUILD) must build
#     the shapedem target only, not the suite; its run line is then run;
#   - the other make lines and bench/run (the suite itself, sanitizer and
#     fuzz builds, regenerating tracked docs, long benchmarks): the target
#     or script must exist (make -n succeeds; bench/run is executable and
#     parses), not run here.
# An analysis that needs more of its run than the shortened one has (the
# hopper's outlet opens at 6.5 s, 1.3 million steps) must refuse it cleanly:
# exit 2 with its one-line reason, no traceback; whole runs must pass.
# A deliberately broken line (a scene that does not exist) is run through
# the same runner and must fail, so the check itself cannot rot.
set -u
bin="$1"
root=$(cd "$2" && pwd)
build=$(cd "$(dirname "$bin")" && pwd)
steps=${README_STEPS:-40}
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_readme.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
work="$tmp/work"
mkdir -p "$work" "$tmp/home"
cp -r "$root/examples" "$root/scripts" "$work/"
mkdir -p "$work/docs/examples"
for d in tests bench; do ln -s "$root/$d" "$work/$d"; done
ln -s "$build" "$work/build"
export HOME="$tmp/home"
export PATH="/usr/bin:/bin:$PATH"  # Debian's python3, the one scripts/deps.sh installs modules for
export PKG_CONFIG_PATH="$HOME/.local/lib/pkgconfig" LD_LIBRARY_PATH="$HOME/.local/lib"
export MPLBACKEND=Agg

# the command blocks, one line each: "LINE<TAB>text"
awk '
  /^```/ { fence = !fence; next }
  fence { next }
  /^    [^ ]/ { blk = blk NR "\t" substr($0, 5) "\n"; if ($0 ~ /[;{}][ \t]*$/) c = 1; next }
  /^    / { next }  # deeper indent: the layout listing'"'"'s continuation
  { if (blk != "" && !c) printf "%s", blk; blk = ""; c = 0 }
  END { if (blk != "" && !c) printf "%s", blk }
' "$root/README.md" | awk -F'\t' '{ split($2, w, " "); if (w[1] !~ /\/$/) print }' >"$tmp/lines"
check "found the README's commands ($(wc -l <"$tmp/lines") lines)" "$(($(wc -l <"$tmp/lines") >= 30))"

shorten() {  # --steps N after each `shapedem run SCENE`
    if [[ $steps == full ]]; then printf '%s' "$1"; else  # shapedem run SCENE --steps N
        sed -E "s#(shapedem run [^ ;]+)#\\1 --steps $steps#g" <<<"$1"; fi
}
run_line() {  # runs one line in the work directory; its output in $tmp/out
    (cd "$work" && timeout 600 bash -c "$(shorten "$1")") </dev/null >"$tmp/out" 2>&1
}

# the library install first: the cc lines above it in the README build against it
grep -q $'\tcmake --install build --prefix ~/.local' "$tmp/lines" && {
    run_line "cmake --install build --prefix ~/.local"
    check "README: cmake --install build --prefix ~/.local (rc $?)" "$(($? == 0))"
}
# the example.c of the install section: the README's C example in a main
awk '/^```c$/{f=1; next} f&&/^```$/{exit} f' "$root/README.md" >"$tmp/body.c"
{ echo '#include <shapedem/shapedem.h>'; echo 'int main(void) {'; cat "$tmp/body.c"; echo 'return 0; }'; } \
    >"$work/example.c"

while IFS=$'\t' read -r no line; do
    word=${line%% *}
    name="README.md:$no: $line"
    case $word in
    make)
        args=${line#make }; args=${args%%#*}
        # shellcheck disable=SC2086  # the README's words
        (cd "$root" && make -n $args BUILD="$build") >"$tmp/recipe" 2>&1
        rc=$?
        if [[ $args =~ ^demo\ *$ ]]; then
            builds=$(grep -c "cmake --build" "$tmp/recipe")
            only=$(grep "cmake --build" "$tmp/recipe" | grep -c -- "--target shapedem$")
            check "$name: the recipe builds only the shapedem target (rc $rc, $builds build(s))" \
                "$([[ $rc == 0 && $builds == 1 && $only == 1 ]] && echo 1 || echo 0)"
            demo=$(grep -E "^$build/shapedem run " "$tmp/recipe" | sed "s#^$build/#build/#")
            run_line "$demo"
            rc=$?
            ((rc == 0)) || tail -5 "$tmp/out"
            check "$name: its run ($demo) exits 0 (got $rc)" "$((rc == 0))"
        else
            check "$name: the target exists (make -n: rc $rc; not run here)" "$((rc == 0))"
        fi
        ;;
    bench/run)
        bash -n "$root/bench/run"
        check "$name: bench/run exists and parses (a long benchmark: not run here)" \
            "$([[ $? == 0 && -x $root/bench/run ]] && echo 1 || echo 0)"
        ;;
    cmake) [[ $line == "cmake --install build --prefix ~/.local"* ]] ||
        check "$name: a cmake line this test does not know" 0 ;;
    mpirun)
        if ! command -v mpirun >/dev/null || [[ ! -x $build/shapedem-mpi ]]; then
            echo "SKIP $name: no Open MPI or no shapedem-mpi in this build"
            continue
        fi
        run_line "$line"
        rc=$?
        ((rc == 0)) || tail -5 "$tmp/out"
        check "$name: exits 0 (got $rc)" "$((rc == 0))"
        ;;
    bash | build/shapedem | python3 | cc | PYTHONPATH=build/python)
        run_line "$line"
        rc=$?
        if [[ $steps != full && $line == "python3 examples/hopper-grid-analyse.py "* ]]; then
            cat "$tmp/out"
            check "$name: on a $steps-step run it refuses cleanly (exit 2, no traceback; got $rc)" \
                "$([[ $rc == 2 ]] && ! grep -q Traceback "$tmp/out" && echo 1 || echo 0)"
            continue
        fi
        ((rc == 0)) || tail -5 "$tmp/out"
        check "$name: exits 0 (got $rc)" "$((rc == 0))"
        ;;
    *) check "$name: starts with '$word', a command this test does not know (add it here)" 0 ;;
    esac
done <"$tmp/lines"

# the runner fails on a broken line
run_line "build/shapedem run examples/no-such-scene.yaml -o out/none"
check "a broken line (a scene that does not exist) fails through the same runner (rc $?)" "$(($? != 0))"
finish
