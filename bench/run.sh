#!/usr/bin/env bash
# The eip2mqtt benchmark: builds a Release tree in build-bench/, then runs every scenario
# against its same-run baseline and writes bench/results/latest.md.
#   bench/run.sh                  full run
#   bench/run.sh --quick          short runs, to check that everything works (results/quick.md)
#   bench/run.sh --only 5         one scenario (numbers as in bench/README.md)
#   bench/run.sh --against REV    the regression guard: builds REV too, in a tree of its own
#                                 (build-bench-against/COMMIT/, reused), and runs each scenario
#                                 on both builds in alternating rounds (combines with the above)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="${EIP2MQTT_BENCH_BUILD:-$root/build-bench}"
jobs="${EIP2MQTT_BENCH_JOBS:-1}"

against=""
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --against) against="${2:?--against needs a revision}"; shift 2 ;;
    --against=*) against="${1#--against=}"; shift ;;
    *) args+=("$1"); shift ;;
  esac
done

# Self-sufficient on a fresh Debian 12 machine, like tools/test.sh: what is missing is installed.
"$root/tools/install-deps.sh"

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DEIP2MQTT_TESTS=OFF \
    -DEIP2MQTT_BENCH=ON >/dev/null
cmake --build "$build" -j "$jobs" --target eip2mqtt bench_load_generator bench_udp_sink \
    bench_mqtt_counter bench_paho_publisher bench_yaml_parse bench_write_latency

# The earlier build: its gateway only. The instruments (load generator, counter, bare Paho)
# stay this tree's, so that both builds are measured by the same ones.
if [ -n "$against" ]; then
  commit="$(git -C "$root" rev-parse --verify --quiet "$against^{commit}")" ||
    { echo "bench/run.sh: --against $against is not a commit of this repository" >&2; exit 2; }
  tree="$build-against/$commit"
  if [ ! -d "$tree/src" ]; then
    rm -rf "$tree/src.partial"
    mkdir -p "$tree/src.partial"
    git -C "$root" archive "$commit" | tar -x -C "$tree/src.partial"
    mv "$tree/src.partial" "$tree/src"
  fi
  cmake -S "$tree/src" -B "$tree/build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DEIP2MQTT_TESTS=OFF -DEIP2MQTT_BENCH=OFF >/dev/null
  cmake --build "$tree/build" -j "$jobs" --target eip2mqtt
  args+=(--against-binary "$tree/build/eip2mqtt"
         --against-label "$(git -C "$root" rev-parse --short "$commit")")
fi
EIP2MQTT_BENCH_BUILD="$build" exec python3 "$here/run.py" "${args[@]}"
