#!/usr/bin/env bash
# checkpoint_h5py.sh — the Python example of docs/checkpoints.md ("Layout
# (HDF5, readable from h5py)") runs as printed, with Debian's h5py
# (python3-h5py, scripts/deps.sh), on a checkpoint of a short run of
# examples/settle-spheres.yaml: only its file name is replaced by the
# checkpoint written. What it reads must be the run's: the step and time
# attributes, 2,028 particles with finite positions inside the box, ids
# 0..2027 once each, every shape -1 (spheres).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
py=/usr/bin/python3  # Debian's interpreter, the one python3-h5py installs into
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# the example: the ```python block after the layout heading
awk '/^## Layout \(HDF5/{s=1} s&&/^```python$/{p=1;next} p&&/^```$/{exit} p' "$root/docs/checkpoints.md" >"$tmp/example.py"
check "found the example in docs/checkpoints.md ($(wc -l <"$tmp/example.py") lines)" \
    "$(grep -q '^import h5py' "$tmp/example.py" && echo 1 || echo 0)"
sed -e 's#^output:#output:\n  checkpoint_every: 100#' "$root/examples/settle-spheres.yaml" >"$tmp/scene.yaml"
"$bin" run "$tmp/scene.yaml" --steps 100 --quiet -o "$tmp/out" >"$tmp/run.log" 2>&1
rc=$?
ck="$tmp/out/checkpoint-000100.h5"
check "a 100-step run writes $(basename "$ck") (rc $rc)" "$([[ $rc == 0 && -s $ck ]] && echo 1 || echo 0)"
grep -o '"out/[^"]*\.h5"' "$tmp/example.py" | head -1 >"$tmp/name"
name=$(tr -d '"' <"$tmp/name")
check "the example opens one checkpoint by name ($name)" "$([[ -n $name ]] && echo 1 || echo 0)"
sed "s#\"$name\"#\"$ck\"#" "$tmp/example.py" >"$tmp/run.py"
cat >>"$tmp/run.py" <<'PY'

import math
ok = (int(f.attrs["step"]) == 100 and abs(float(f.attrs["time"]) - 100 * 5e-6) < 1e-12
      and n == 2028 and x.shape == (n, 3)
      and all(math.isfinite(v) and -1e-3 < v < 0.1 for v in x.flatten())
      and sorted(int(i) for i in ids) == list(range(n))
      and all(int(s) == -1 for s in shape) and isinstance(names, list))
print("read: step %s, time %s, %d particles, x %s, shapes %s: %s"
      % (f.attrs["step"], f.attrs["time"], n, x.shape, sorted(set(int(s) for s in shape)), "ok" if ok else "WRONG"))
raise SystemExit(0 if ok else 1)
PY
"$py" "$tmp/run.py"
rc=$?
check "the example runs with $py and h5py and reads the run's checkpoint (rc $rc)" "$((rc == 0))"
finish
