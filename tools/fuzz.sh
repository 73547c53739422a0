#!/usr/bin/env bash
# Builds the libFuzzer targets (in the sanitizer build, tools/build.sh asan) and runs each for a bounded time on a
# copy of its seed corpus, so that the checked-in corpora are never rewritten; as many at once
# as there are cores (each fuzzer is one process on one core). Fails once the running ones end
# if any crashed, leaked, reported a sanitizer error or timed out; the crashing input is kept
# under build-asan/artifacts/.
#   FUZZ_SECONDS=30 tools/fuzz.sh [target...]   (default: every target)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(capture_frame command_pdu decode_datagram engineering_value journal_samples load_config
    point_list sparkplug_command sparkplug_node text_value topic_template write_payload write_router)
fi

# Only the fuzz targets (and the libraries they link): not the daemon nor the tools.
tools/build.sh asan "${targets[@]/%/_fuzz}"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p build-asan/artifacts

fuzz() {
  local target=$1
  cp -r "tests/fuzz/corpus/$target" "$work/$target"
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} \
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    "build-asan/tests/fuzz/${target}_fuzz" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="build-asan/artifacts/${target}-" \
      "$work/$target" >"$work/$target.log" 2>&1
}

# Reports one finished fuzzer; returns its status.
report() {
  local target=$1 status=$2 log="$work/$1.log"
  if [ "$status" -ne 0 ]; then
    cat "$log" >&2
    echo "fuzzing $target failed (exit $status); inputs in build-asan/artifacts/" >&2
    return "$status"
  fi
  echo "-- $target: ${seconds}s"
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|Done)" "$log" || tail -n 3 "$log"
}

parallel=$(nproc)
failed=0
pids=() names=()
for target in "${targets[@]}"; do
  fuzz "$target" &
  pids+=($!) names+=("$target")
  if [ ${#pids[@]} -ge "$parallel" ]; then
    status=0
    wait "${pids[0]}" || status=$?
    report "${names[0]}" "$status" || failed=$status
    pids=("${pids[@]:1}") names=("${names[@]:1}")
    [ "$failed" -eq 0 ] || break
  fi
done
for i in "${!pids[@]}"; do
  status=0
  wait "${pids[$i]}" || status=$?
  report "${names[$i]}" "$status" || failed=$status
done
[ "$failed" -eq 0 ] || exit "$failed"
echo "fuzzing: ${#targets[@]} target(s) ran ${seconds}s each without a finding"
