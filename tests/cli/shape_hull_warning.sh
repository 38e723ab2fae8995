#!/usr/bin/env bash
# shape_hull_warning.sh — a non-convex mesh taken as its hull
# (`nonconvex: hull`) is accepted with a warning, and every command says so:
# `shape info` (its warning line), `check` (in its warnings, "check: ok,
# with warnings") and `run` (one "warning:" line on stderr, exit 0).
set -u
bin="$1"
root="$2"
[[ $bin == */* ]] && bin=$(cd "$(dirname "$bin")" && pwd)/$(basename "$bin")
root=$(cd "$root" && pwd)
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d "${TMPDIR:-/tmp}/sd_shape_hull.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
cp "$root/tests/cli/bad/nonconvex-mesh.obj" "$tmp/"
cat >"$tmp/hull.yaml" <<'EOF'
simulation: {dt: 1.0e-6, steps: 5}
materials: [{name: glass, density: 2500, youngs_modulus: 1.0e7}]
shapes:
  - {name: dented, type: polyhedron, file: nonconvex-mesh.obj, scale: 0.001, nonconvex: hull}
particles: [{generator: list, material: glass, shape: dented, spheres: [{position: [0, 0, 0.01]}]}]
EOF
cd "$tmp" || exit 1
out=$("$bin" shape info hull.yaml 2>&1)
rc=$?
check "shape info: exit 0 (got $rc), a warning line" "$([[ $rc == 0 ]] && grep -c '^warning .*not convex' <<<"$out" || echo 0)"
out=$("$bin" check hull.yaml 2>"$tmp/check.err")
rc=$?
check "check: exit 0 (got $rc), the warning among its warnings" \
    "$([[ $rc == 0 ]] && grep -c '^warning *shape dented: .*not convex.*convex hull' <<<"$out" || echo 0)"
check "check: 'check: ok, with warnings'" "$(grep -c '^check: ok, with warnings$' <<<"$out")"
"$bin" run hull.yaml -o "$tmp/out" >/dev/null 2>"$tmp/run.err"
rc=$?
nw=$(grep -c '^shapedem: warning: shape dented: .*not convex.*convex hull' "$tmp/run.err")
check "run: exit 0 (got $rc), one warning line on stderr (got $nw)" "$([[ $rc == 0 && $nw == 1 ]] && echo 1 || echo 0)"
# a convex mesh: no warning anywhere
cat >"$tmp/cube.obj" <<'EOF'
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
EOF
sed -e 's/nonconvex-mesh.obj/cube.obj/' hull.yaml >cube.yaml
out=$("$bin" check cube.yaml 2>&1)
rc=$?
check "a convex mesh: check exit 0 (got $rc), no shape warning" \
    "$([[ $rc == 0 && $(grep -c 'shape dented' <<<"$out") == 0 ]] && echo 1 || echo 0)"
"$bin" run cube.yaml -o "$tmp/out2" >/dev/null 2>"$tmp/run2.err"
rc=$?
check "a convex mesh: run exit 0 (got $rc), stderr empty" "$([[ $rc == 0 && ! -s $tmp/run2.err ]] && echo 1 || echo 0)"
finish
