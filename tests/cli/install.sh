#!/usr/bin/env bash
# install.sh — the installed library works the way the README says: the
# build tree this test runs from (the shapedem binary's directory) is
# installed with `cmake --install` into a temporary prefix, and programs are
# built against that prefix only, never against the source tree:
#   - each installed public header compiles alone, twice included, as C17 and
#     as C++17, with -Wall -Wextra -Werror -pedantic;
#   - shapedem.pc: version, prefix, and a shared library with its SONAME;
#   - the README's library example (the text between the marker comments of
#     tests/unit/readme_example.c, checked to be the README's text) built with
#     the README's pkg-config compile line, shared and --static, run: it must
#     print the free-fall height z = 0.01 - g t^2 / 2 after 10 ms;
#   - a CMake project with find_package(shapedem CONFIG) linking
#     shapedem::shapedem and shapedem::shapedem_static, built and run;
#   - the installed CLI checks and runs a short copy of
#     examples/settle-spheres.yaml;
#   - the scene-loading example examples/c/run_scene.c built the same way and
#     run on that scene: it writes the run's files, and the same stats.csv as
#     the CLI.
# Everything is made in a temporary directory removed at exit.
set -u
bin="$1"
root=$(cd "$2" && pwd)  # absolute: the test works in its temporary directory
build=$(cd "$(dirname "$bin")" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
ok() { [[ $1 == 0 ]] && echo 1 || echo 0; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_install.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
log="$tmp/log"

cmake --install "$build" --prefix "$prefix" >"$log" 2>&1
rc=$?
check "cmake --install into a temporary prefix exits 0 (got $rc)" "$(ok $rc)"
((rc == 0)) || { tail -5 "$log"; echo "$pass passed, $fail failed"; exit 1; }

# the layout: GNUInstallDirs may choose lib or lib/<multiarch>
pc=$(find "$prefix" -name shapedem.pc -path '*/pkgconfig/*' | head -1)
libdir=$(dirname "$(dirname "$pc")")
check "installed: include/shapedem/shapedem.h, bin/shapedem" \
    "$([[ -f $prefix/include/shapedem/shapedem.h && -x $prefix/bin/shapedem ]] && echo 1 || echo 0)"
check "installed: shapedem.pc, libshapedem.a, libshapedem.so (in ${libdir#"$prefix"/})" \
    "$([[ -n $pc && -f $libdir/libshapedem.a && -e $libdir/libshapedem.so ]] && echo 1 || echo 0)"
check "installed: shapedemConfig.cmake and its version file" \
    "$([[ -f $libdir/cmake/shapedem/shapedemConfig.cmake && -f $libdir/cmake/shapedem/shapedemConfigVersion.cmake ]] && echo 1 || echo 0)"
n_src=$(find "$root/include/shapedem" -name '*.h' | wc -l)
n_inst=$(find "$prefix/include" -type f | wc -l)
check "only the public headers installed ($n_inst files for $n_src in include/shapedem)" \
    "$([[ $n_inst == "$n_src" ]] && echo 1 || echo 0)"

# each public header on its own, as C and as C++ (extern "C" guards)
for h in "$prefix"/include/shapedem/*.h; do
    name=shapedem/$(basename "$h")
    printf '#include <%s>\n#include <%s>\nint sd_install_probe(void);\nint sd_install_probe(void) { return 0; }\n' \
        "$name" "$name" >"$tmp/probe.c"
    cc -std=c17 -Wall -Wextra -Werror -pedantic -c "$tmp/probe.c" -I"$prefix/include" -o "$tmp/probe.o" >"$log" 2>&1
    rc=$?
    check "$name compiles alone as C17 (got $rc)" "$(ok $rc)"
    ((rc == 0)) || head -5 "$log"
    c++ -std=c++17 -Wall -Wextra -Werror -pedantic -x c++ -c "$tmp/probe.c" -I"$prefix/include" -o "$tmp/probe.o" >"$log" 2>&1
    rc=$?
    check "$name compiles alone as C++17 (got $rc)" "$(ok $rc)"
    ((rc == 0)) || head -5 "$log"
done

export PKG_CONFIG_PATH="$libdir/pkgconfig"
ver=$(pkg-config --modversion shapedem 2>/dev/null)
hver=$(sed -n 's/^#define SD_VERSION_STRING "\(.*\)"$/\1/p' "$prefix/include/shapedem/shapedem.h")
check "pkg-config --modversion shapedem is the header's SD_VERSION_STRING (got '$ver', header '$hver')" \
    "$([[ -n $ver && $ver == "$hver" ]] && echo 1 || echo 0)"
pcprefix=$(pkg-config --variable=prefix shapedem 2>/dev/null)
check "shapedem.pc names the install prefix" "$([[ $pcprefix == "$prefix" ]] && echo 1 || echo 0)"
soname=$(readelf -d "$libdir/libshapedem.so" 2>/dev/null | sed -n 's/.*(SONAME).*\[\(.*\)\]/\1/p')
check "libshapedem.so has a SONAME with the version ($soname)" \
    "$([[ $soname == libshapedem.so.* && -e $libdir/$soname ]] && echo 1 || echo 0)"

# the README example: the marked text of tests/unit/readme_example.c, which
# must also be the start of the README's C block, in a main() that prints the
# sphere's height
sed -n '/README example begins/,/README example ends/p' "$root/tests/unit/readme_example.c" |
    sed '1d;$d; s/^    //' >"$tmp/snippet.c"
sed -n '/^## Library/,/^## /p' "$root/README.md" | sed -n '/^```c$/,/^```$/p' | sed '1d;$d' >"$tmp/readme_block.c"
n=$(wc -l <"$tmp/snippet.c")
check "the README's C example starts with the $n lines of tests/unit/readme_example.c" \
    "$([[ $n -gt 5 ]] && head -n "$n" "$tmp/readme_block.c" | cmp -s - "$tmp/snippet.c" && echo 1 || echo 0)"
{
    printf '#include <shapedem/shapedem.h>\n#include <stdio.h>\n\nint main(void)\n{\n'
    sed 's/^/    /' "$tmp/snippet.c"
    printf '    sd_particle_state p;\n'
    printf '    if (sd_world_get_particle(w, 0, &p) != SD_OK) return 1;\n'
    printf '    printf("z %%.12f\\n", p.position.z);\n'
    printf '    sd_world_destroy(w);\n    return 0;\n}\n'
} >"$tmp/example.c"
# 10 ms of free fall from 1 cm: z = 0.01 - 9.81 * 1e-4 / 2 (readme_example.c's check)
height_ok() { awk -v z="$(awk '/^z / {print $2}' <<<"$1")" 'BEGIN {print (z != "" && z > 0.00950950 - 1e-9 && z < 0.00950950 + 1e-9)}'; }

cd "$tmp" || exit 1
# shellcheck disable=SC2046 # the flags are meant to split
cc example.c $(pkg-config --cflags --libs shapedem) -o example_shared >"$log" 2>&1
rc=$?
check "README line: cc example.c \$(pkg-config --cflags --libs shapedem) exits 0 (got $rc)" "$(ok $rc)"
((rc == 0)) || head -5 "$log"
needed=$(readelf -d example_shared 2>/dev/null | grep -c "NEEDED.*\[libshapedem.so")
check "the pkg-config program links the shared library" "$([[ $needed == 1 ]] && echo 1 || echo 0)"
out=$(LD_LIBRARY_PATH="$libdir" ./example_shared 2>&1)
check "shared README example prints z = 0.00950950 m ($out)" "$(height_ok "$out")"
if grep -q '^SHAPEDEM_SANITIZE:BOOL=ON$' "$build/CMakeCache.txt" 2>/dev/null; then
    echo "SKIP cc -static: the sanitizer runtimes do not link into a static program"
else
    # shellcheck disable=SC2046
    cc -static example.c $(pkg-config --static --cflags --libs shapedem) -o example_static >"$log" 2>&1
    rc=$?
    check "README line: cc -static example.c \$(pkg-config --static --cflags --libs shapedem) exits 0 (got $rc)" "$(ok $rc)"
    ((rc == 0)) || head -5 "$log"
    needed=$(readelf -d example_static 2>/dev/null | grep -c NEEDED)
    check "the --static program needs no shared library (got $needed)" "$([[ $needed == 0 ]] && echo 1 || echo 0)"
    out=$(./example_static 2>&1)
    check "static README example prints z = 0.00950950 m ($out)" "$(height_ok "$out")"
fi

# a CMake project against the prefix
mkdir -p "$tmp/cmake-project"
cp example.c "$tmp/cmake-project/"
cat >"$tmp/cmake-project/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.18)
project(sd_consumer LANGUAGES C)
find_package(shapedem 0.1 CONFIG REQUIRED)
add_executable(example_shared example.c)
target_link_libraries(example_shared PRIVATE shapedem::shapedem)
add_executable(example_static example.c)
target_link_libraries(example_static PRIVATE shapedem::shapedem_static)
EOF
cmake -S "$tmp/cmake-project" -B "$tmp/cmake-build" -DCMAKE_PREFIX_PATH="$prefix" >"$log" 2>&1 &&
    cmake --build "$tmp/cmake-build" >>"$log" 2>&1
rc=$?
check "CMake project with find_package(shapedem CONFIG) configures and builds (got $rc)" "$(ok $rc)"
((rc == 0)) || tail -8 "$log"
out=$("$tmp/cmake-build/example_shared" 2>&1)
check "shapedem::shapedem program prints z = 0.00950950 m ($out)" "$(height_ok "$out")"
out=$("$tmp/cmake-build/example_static" 2>&1)
check "shapedem::shapedem_static program prints z = 0.00950950 m ($out)" "$(height_ok "$out")"
needed=$(readelf -d "$tmp/cmake-build/example_static" 2>/dev/null | grep -c "NEEDED.*\[libshapedem.so")
check "shapedem::shapedem_static links no libshapedem.so" "$([[ $needed == 0 ]] && echo 1 || echo 0)"

# a short copy of the settle-spheres example
sed -e 's/^  duration: .*/  steps: 200/' -e "s|^  directory: .*|  directory: $tmp/out-cli|" \
    -e 's/^  every: .*/  every: 50/' -e 's/^  stats_every: .*/  stats_every: 25/' \
    "$root/examples/settle-spheres.yaml" >"$tmp/settle-short.yaml"
"$prefix/bin/shapedem" check "$tmp/settle-short.yaml" >"$log" 2>&1
rc=$?
check "installed shapedem checks a short settle-spheres scene (got $rc)" "$(ok $rc)"
((rc == 0)) || head -3 "$log"
"$prefix/bin/shapedem" run "$tmp/settle-short.yaml" --threads 2 --quiet >"$log" 2>&1
rc=$?
check "installed shapedem runs it (got $rc), writing stats.csv" "$([[ $rc == 0 && -s $tmp/out-cli/stats.csv ]] && echo 1 || echo 0)"
((rc == 0)) || head -3 "$log"

# the scene-loading example, built against the prefix like the README
# example, and the same scene run by the installed CLI: the same stats.csv
if [[ -f $root/examples/c/run_scene.c ]]; then
    # shellcheck disable=SC2046
    cc -std=c17 -Wall -Wextra -Werror "$root/examples/c/run_scene.c" $(pkg-config --cflags --libs shapedem) \
        -o run_scene >"$log" 2>&1
    rc=$?
    check "examples/c/run_scene.c builds against the prefix with pkg-config (got $rc)" "$(ok $rc)"
    ((rc == 0)) || head -5 "$log"
    out=$(OMP_NUM_THREADS=2 LD_LIBRARY_PATH="$libdir" ./run_scene "$tmp/settle-short.yaml" "$tmp/out-lib" 2>&1)
    rc=$?
    check "run_scene runs the short scene (got $rc) and reports its 2028 particles" \
        "$([[ $rc == 0 ]] && grep -c '^particles 2028$' <<<"$out" || echo 0)"
    ((rc == 0)) || head -5 <<<"$out"
    for f in summary.txt stats.csv frames.pvd; do
        check "run_scene wrote $f" "$([[ -s $tmp/out-lib/$f ]] && echo 1 || echo 0)"
    done
    check "run_scene's stats.csv is the CLI's, byte for byte" \
        "$(cmp -s "$tmp/out-lib/stats.csv" "$tmp/out-cli/stats.csv" && echo 1 || echo 0)"
else
    echo "SKIP scene example: examples/c/run_scene.c not present"
fi

finish
