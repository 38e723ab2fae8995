#!/usr/bin/env bash
# threads_policy.sh — `check` says how many OpenMP threads run and why, and
# more threads than free cores wait passively (src/cli/threads.c, issue 31):
#   - --threads 1, OMP_NUM_THREADS and the default each named as the reason;
#     the default is all the cores or the free ones, with the count it names;
#   - --threads (or simulation.threads) above the cores: the program starts itself again with
#     OMP_WAIT_POLICY=passive, seen in the environment of the running
#     process (/proc/PID/environ), where libgomp reads it, and check says so;
#   - a policy the user set (OMP_WAIT_POLICY, GOMP_SPINCOUNT) is kept.
# No timing is asserted (bench/threads_load measures them).
set -u
bin="$1"
root="$2"
. "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/lib.sh"  # pass, fail, check NAME 0|1, finish
tmp=$(mktemp -d)
pid=""
trap '[[ -n $pid ]] && kill "$pid" 2>/dev/null; rm -rf "$tmp"' EXIT
scene="$root/examples/settle-spheres.yaml"
cores=$(nproc)
over=$((cores + 1))
line() { grep '^threads ' "$tmp/out"; }
clean=(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT -u OMP_NUM_THREADS)

"${clean[@]}" "$bin" check "$scene" --threads 1 >"$tmp/out" 2>&1
echo "  $(line)"
one='^threads +1 thread [(]--threads 1[)]$'
check "--threads 1: '1 thread (--threads 1)', no wait policy" "$([[ $(line) =~ $one ]] && echo 1 || echo 0)"

"${clean[@]}" OMP_NUM_THREADS=1 "$bin" check "$scene" >"$tmp/out" 2>&1
echo "  $(line)"
check "OMP_NUM_THREADS=1: named as the reason" \
    "$([[ $(line) == *"1 thread (from OMP_NUM_THREADS)"* ]] && echo 1 || echo 0)"

"${clean[@]}" "$bin" check "$scene" >"$tmp/out" 2>&1
l=$(line)
echo "  $l"
ok=0
all='^threads +([0-9]+) threads? [(]all ([0-9]+) cores[)]$'
free='^threads +([0-9]+) threads? [(]([0-9]+) of ([0-9]+) cores free: '
if [[ $l =~ $all ]]; then
    [[ ${BASH_REMATCH[1]} == "$cores" && ${BASH_REMATCH[2]} == "$cores" ]] && ok=1
elif [[ $l =~ $free ]]; then
    [[ ${BASH_REMATCH[1]} == "${BASH_REMATCH[2]}" && ${BASH_REMATCH[3]} == "$cores" ]] && ok=1
fi
check "the default: all $cores cores, or the free ones it names, on as many threads" "$ok"

"${clean[@]}" "$bin" check "$scene" --threads "$over" >"$tmp/out" 2>&1
echo "  $(line)"
check "--threads $over on $cores cores: check says the threads wait passively" \
    "$([[ $(line) == *"$over threads (--threads $over); waiting passively"* ]] && echo 1 || echo 0)"

# the running program's environment: what libgomp read when it loaded
"${clean[@]}" "$bin" run "$scene" --threads "$over" --quiet -o "$tmp/run" >/dev/null 2>&1 &
pid=$!
env_of() { tr '\0' '\n' <"/proc/$pid/environ" 2>/dev/null | grep '^OMP_WAIT_POLICY=' || true; }
seen=""
for _ in $(seq 50); do
    sleep 0.2
    seen=$(env_of)
    [[ -n $seen ]] && break
done
kill "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
pid=""
check "run --threads $over: the process runs with OMP_WAIT_POLICY=passive (saw '${seen:-nothing}')" \
    "$([[ $seen == OMP_WAIT_POLICY=passive ]] && echo 1 || echo 0)"

# simulation.threads is read after the start: the scene's count restarts too
sed -e "s#^simulation:#simulation:\n  threads: $over#" "$scene" >"$tmp/scene.yaml"
"${clean[@]}" "$bin" check "$tmp/scene.yaml" >"$tmp/out" 2>&1
echo "  $(line)"
check "simulation.threads: $over on $cores cores: named, and the threads wait passively" \
    "$([[ $(line) == *"$over threads (simulation.threads); waiting passively"* ]] && echo 1 || echo 0)"

"${clean[@]}" OMP_WAIT_POLICY=active "$bin" check "$scene" --threads "$over" >"$tmp/out" 2>&1
echo "  $(line)"
check "OMP_WAIT_POLICY=active set by the user: kept and named" \
    "$([[ $(line) == *"waiting as OMP_WAIT_POLICY=active" ]] && echo 1 || echo 0)"
"${clean[@]}" GOMP_SPINCOUNT=1000 "$bin" check "$scene" --threads "$over" >"$tmp/out" 2>&1
echo "  $(line)"
check "GOMP_SPINCOUNT set by the user: kept and named" \
    "$([[ $(line) == *"waiting as GOMP_SPINCOUNT=1000" ]] && echo 1 || echo 0)"
finish
