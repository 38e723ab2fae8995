#!/usr/bin/env bash
# sd_hd_libm.sh — the single-source numerics call no libm function that
# CUDA's math library rounds differently (docs/architecture.md, "Same bits
# on CPU and GPU"): in the SD_HD headers (src/core, src/shape/*.h,
# src/geom/*.h, src/contact, src/dynamics, src/backend/items.h,
# src/grid/stencil.h), comments stripped, no call of sin, cos, tan, their
# inverses and hyperbolic forms, exp, log, pow, cbrt, hypot, erf, tgamma
# (plain, f-suffixed or through sd_pow, sd_exp, sd_log, sd_host_*): they
# use sd_sin, sd_cos, sd_atan2, sd_cbrt (core/math.h). sqrt, fabs, floor
# and ceil are exact on both and allowed. core/math.h itself is the one
# place that implements them; core/base.h must map sd_sin, sd_cos,
# sd_atan2 and sd_cbrt to it in the double build.
set -u
src="$2"
cd "$src" || exit 1
python3 - <<'PY'
import glob, re, sys
files = sorted(set(glob.glob("src/core/*.h") + glob.glob("src/shape/*.h") + glob.glob("src/geom/*.h")
                   + glob.glob("src/contact/*.h") + glob.glob("src/dynamics/*.h")
                   + ["src/backend/items.h", "src/grid/stencil.h"]))
files = [f for f in files if f != "src/core/math.h"]
names = r"(?:a?sinh?|a?cosh?|a?tanh?|atan2|exp|exp2|expm1|log|log2|log10|log1p|pow|cbrt|hypot|erfc?|tgamma|lgamma)f?"
call = re.compile(r"(?<![\w.>])(?:sd_(?:pow|exp|log|host_\w+)|" + names + r")\s*\(")
bad = 0
for f in files:
    text = open(f, encoding="utf-8").read()
    # strip comments, keeping line numbers
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    for no, line in enumerate(text.split("\n"), 1):
        if line.lstrip().startswith("#define"):
            continue
        for m in call.finditer(line):
            print(f"FAIL {f}:{no}: {m.group(0)}  ({line.strip()[:80]})")
            bad += 1
print(f"{'PASS' if bad == 0 else 'FAIL'} {len(files)} SD_HD headers: {bad} calls of libm's rounded functions")
base = open("src/core/base.h", encoding="utf-8").read()
for fn in ("sin", "cos", "atan2", "cbrt"):
    ok = re.search(r"#define sd_%s sd_math_%s\b" % (fn, fn), base) is not None
    print(f"{'PASS' if ok else 'FAIL'} core/base.h: sd_{fn} is sd_math_{fn} in the double build")
    bad += 0 if ok else 1
sys.exit(1 if bad else 0)
PY
