#!/usr/bin/env bash
# Runs each libFuzzer target for a while (`make fuzz`).
#
#   tests/fuzz/run.sh BUILD SECONDS [NAME...]     (default: every target)
#
# BUILD is a build directory configured with -DSHAPEDEM_FUZZ=ON (clang);
# each target BUILD/tests/fuzz/fuzz_NAME runs for SECONDS on one core, one
# after the other, starting from tests/fuzz/corpus/NAME and
# tests/fuzz/regress/NAME. New inputs go to BUILD/fuzz/corpus/NAME (kept
# between runs, never into the tree); a crash, leak or sanitizer report
# leaves its input in BUILD/fuzz/crashes/NAME/. To keep a finding as a
# regression test, fix the bug and copy the input to tests/fuzz/regress/NAME/
# (fuzz.replay.NAME then runs it in `make test`).
#
# Exit status: 0 when every target ran its time without a finding, 1
# otherwise (each finding named at the end).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
build=${1:?usage: run.sh BUILD SECONDS [NAME...]}
seconds=${2:?usage: run.sh BUILD SECONDS [NAME...]}
shift 2
names=("$@")
if [[ ${#names[@]} -eq 0 ]]; then
  names=(scene mesh outline csv checkpoint frame motion)
fi
# The targets write each input to a file: on tmpfs when there is one.
if [[ -z ${TMPDIR:-} && -d /dev/shm && -w /dev/shm ]]; then
  export TMPDIR=/dev/shm
fi
failed=()
for name in "${names[@]}"; do
  exe=$build/tests/fuzz/fuzz_$name
  if [[ ! -x $exe ]]; then
    echo "fuzz: $exe is missing (configure $build with -DSHAPEDEM_FUZZ=ON and build fuzz_programs)" >&2
    exit 1
  fi
  work=$build/fuzz/corpus/$name crashes=$build/fuzz/crashes/$name
  mkdir -p "$work" "$crashes"
  dict=()
  [[ -f $here/$name.dict ]] && dict=(-dict="$here/$name.dict")
  echo "fuzz: $name for ${seconds} s" >&2
  # -timeout: an input taking over 10 s is a finding (a reader must not
  # hang); -rss_limit_mb: nor take 2 GiB; -max_len: the seeds' order of
  # size (a checkpoint is mostly HDF5 metadata, tens of KiB).
  max_len=8192
  [[ $name == checkpoint ]] && max_len=65536
  # The log keeps libFuzzer's report; its last lines say how it went.
  log=$build/fuzz/$name.log
  "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=$max_len -print_final_stats=1 \
    -artifact_prefix="$crashes/" "${dict[@]}" "$work" "$here/corpus/$name" "$here/regress/$name" >"$log" 2>&1
  rc=$?
  grep -E '^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+ +DONE' "$log" | sed "s/^/fuzz: $name: /" >&2
  if [[ $rc -ne 0 ]]; then
    failed+=("$name")
    echo "fuzz: $name FOUND something (exit $rc): see $log; inputs in $crashes:" >&2
    ls "$crashes" >&2
  fi
done
if [[ ${#failed[@]} -ne 0 ]]; then
  echo "fuzz: findings in: ${failed[*]}" >&2
  exit 1
fi
echo "fuzz: no finding in ${names[*]} (${seconds} s each)" >&2
