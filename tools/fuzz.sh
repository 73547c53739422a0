#!/usr/bin/env bash
# Builds the libFuzzer targets (tools/build.sh fuzz, clang) and runs each for a bounded time on a
# copy of its seed corpus, so that the checked-in corpora are never rewritten. Fails on the first
# crash, leak, sanitizer report or timeout; the crashing input is kept under build-fuzz/artifacts/.
#   FUZZ_SECONDS=30 tools/fuzz.sh [target...]   (default: every target)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${FUZZ_SECONDS:-30}
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  targets=(capture_frame command_pdu decode_datagram journal_samples load_config point_list
    sparkplug_command sparkplug_node write_payload write_router)
fi

tools/build.sh fuzz

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p build-fuzz/artifacts
for target in "${targets[@]}"; do
  echo "-- fuzzing $target for ${seconds}s"
  cp -r "tests/fuzz/corpus/$target" "$work/$target"
  log="$work/$target.log"
  status=0
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} \
  UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1} \
    "build-fuzz/tests/fuzz/${target}_fuzz" \
      -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="build-fuzz/artifacts/${target}-" \
      "$work/$target" >"$log" 2>&1 || status=$?
  if [ "$status" -ne 0 ]; then
    cat "$log" >&2
    echo "fuzzing $target failed (exit $status); inputs in build-fuzz/artifacts/" >&2
    exit "$status"
  fi
  grep -E "^(#[0-9]+ +DONE|stat::number_of_executed_units|Done)" "$log" || tail -n 3 "$log"
done
echo "fuzzing: ${#targets[@]} target(s) ran ${seconds}s each without a finding"
