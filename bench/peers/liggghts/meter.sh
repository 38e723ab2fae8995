#!/usr/bin/env bash
# Usage: meter.sh DIR COMMAND [ARGS...]
# Runs COMMAND and writes its peak resident set in kB to DIR/peak-rss.<pid>,
# one file per process, so that the ranks under mpirun do not interleave their
# reports. GNU time measures it when present; otherwise the process's VmHWM is
# read from /proc every 0.1 s (the last reading before exit is the peak unless
# memory grew in the final tenth of a second).
dir=$1
shift
if [[ -x /usr/bin/time ]] && /usr/bin/time -f '%M' -o /dev/null true 2>/dev/null; then
  exec /usr/bin/time -f '%M' -o "$dir/peak-rss.$$" "$@"
fi
"$@" &
pid=$!
hwm=0
while kill -0 "$pid" 2>/dev/null; do
  v=$(awk '/^VmHWM:/ {print $2}' "/proc/$pid/status" 2>/dev/null)
  [[ -n "$v" ]] && hwm=$v
  sleep 0.1
done
wait "$pid"
rc=$?
echo "$hwm" >"$dir/peak-rss.$$"
exit $rc
