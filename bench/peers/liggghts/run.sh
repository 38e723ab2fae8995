#!/usr/bin/env bash
# Runs the spheres-settle case with LIGGGHTS and prints one JSON line:
#   {"case":...,"code":"liggghts","particles":N,"steps":S,"procs":P,"wall_s":X,
#    "psps":Y,"peak_rss_mib":Z,"load1":L}
# wall_s is LIGGGHTS's own "Loop time" (the stepping loop only, no setup);
# psps = particles * steps / wall_s; peak_rss_mib is the sum over the P processes
# of each one's peak resident set. On failure it prints a line with "error".
#
# Usage: bench/peers/liggghts/run.sh N STEPS PROCS [WORKDIR [SIDE]]
#   N      number of spheres, a multiple of SIDE^2 (SIDE x SIDE per layer)
#   STEPS  time steps to run
#   PROCS  MPI processes (1 runs the binary directly, more go through mpirun)
#   WORKDIR where the data file and the log go (default: bench/out/liggghts)
#   SIDE   spheres along x and y in a layer (default 20: a 44 mm box)
# Environment: SHAPEDEM_LIGGGHTS (binary, default liggghts),
#              SHAPEDEM_MPIRUN (launcher, default mpirun).
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
n=${1:?usage: run.sh N STEPS PROCS [WORKDIR]}
steps=${2:?usage: run.sh N STEPS PROCS [WORKDIR]}
procs=${3:?usage: run.sh N STEPS PROCS [WORKDIR]}
work=${4:-$here/../../out/liggghts}
side=${5:-20}
case_name="spheres-settle-$n"
lmp=${SHAPEDEM_LIGGGHTS:-liggghts}
mpirun_bin=${SHAPEDEM_MPIRUN:-mpirun}

fail() {
  printf '{"case":"%s","code":"liggghts","particles":%s,"steps":%s,"procs":%s,"error":"%s"}\n' \
    "$case_name" "$n" "$steps" "$procs" "$1"
  exit 1
}

command -v "$lmp" >/dev/null 2>&1 ||
  fail "LIGGGHTS not found ($lmp); install it: SHAPEDEM_WITH_BENCH=1 make deps, or apt-get install -y liggghts"

mkdir -p "$work" || fail "cannot create $work"
work=$(cd "$work" && pwd)
data="$work/spheres-$n.data"
log="$work/$case_name-np$procs.log"

# Written afresh each time (under a second, outside the timed loop), so that it
# always matches gen-data.awk.
{ awk -v n="$n" -v seed=42 -v zmax=0.5 -v side="$side" -f "$here/gen-data.awk" >"$data.tmp" &&
  mv "$data.tmp" "$data"; } || fail "cannot write the data file"

# Peak RSS: meter.sh writes one file per process into $rss_dir.
rss_dir="$work/rss-np$procs"
{ rm -rf "$rss_dir" && mkdir -p "$rss_dir"; } || fail "cannot create $rss_dir"

launcher=()
if ((procs > 1)); then
  command -v "$mpirun_bin" >/dev/null 2>&1 || fail "mpirun not found for $procs processes"
  launcher=("$mpirun_bin" -np "$procs")
  if "$mpirun_bin" --version 2>/dev/null | grep -q 'Open MPI'; then
    # Open MPI refuses root without this, and counts cores strictly.
    launcher=("$mpirun_bin" --allow-run-as-root --oversubscribe -np "$procs")
  fi
fi

load1=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo null)
# Run inside $work so that any file LIGGGHTS might write lands there; -log none
# keeps it from writing log.liggghts, and the script writes no dumps.
(cd "$work" && "${launcher[@]}" bash "$here/meter.sh" "$rss_dir" "$lmp" -in "$here/in.spheres-settle" \
  -var data "$data" -var steps "$steps" -var width "$(awk -v s="$side" 'BEGIN {printf "%.6g", s * 0.0022}')" \
  -log none -echo none) >"$log" 2>&1
rc=$?

loop=$(grep -m1 '^Loop time of' "$log")
[[ $rc -eq 0 && -n "$loop" ]] || fail "liggghts exited with status $rc; see $log"

# "Loop time of X on P procs for S steps with N atoms"
read -r wall p_got s_got n_got < <(awk '{print $4, $6, $9, $12}' <<<"$loop")
[[ "$p_got" == "$procs" && "$s_got" == "$steps" ]] || fail "unexpected loop line: $loop"
awk -v w="$wall" 'BEGIN {exit !(w > 0)}' || fail "loop time too short to measure: $loop"
rss_kb=$(cat "$rss_dir"/peak-rss.* 2>/dev/null | awk '{s += $1} END {print s + 0}')

awk -v c="$case_name" -v n="$n_got" -v s="$s_got" -v p="$p_got" -v w="$wall" \
  -v r="$rss_kb" -v l="$load1" 'BEGIN {
    printf "{\"case\":\"%s\",\"code\":\"liggghts\",\"particles\":%d,\"steps\":%d,\"procs\":%d,", c, n, s, p
    printf "\"wall_s\":%.4f,\"psps\":%.4g,\"peak_rss_mib\":%s,\"load1\":%s}\n", w, n * s / w,
      (r > 0 ? sprintf("%.1f", r / 1024) : "null"), l
  }'
