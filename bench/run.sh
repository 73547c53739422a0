#!/usr/bin/env bash
# The eip2mqtt benchmark (issue #6): builds a Release tree in build-bench/, then runs every
# scenario against its same-run baseline and writes bench/results/latest.md.
#   bench/run.sh            full run (~5 minutes)
#   bench/run.sh --quick    short runs, to check that everything works (results/quick.md)
#   bench/run.sh --only 5   one scenario (numbers as in bench/README.md)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(dirname "$here")"
build="${EIP2MQTT_BENCH_BUILD:-$root/build-bench}"
jobs="${EIP2MQTT_BENCH_JOBS:-1}"

# Self-sufficient on a fresh Debian 12 machine, like tools/test.sh: what is missing is installed.
"$root/tools/install-deps.sh"

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DEIP2MQTT_TESTS=OFF \
    -DEIP2MQTT_BENCH=ON >/dev/null
cmake --build "$build" -j "$jobs" --target eip2mqtt bench_load_generator bench_udp_sink \
    bench_mqtt_counter bench_paho_publisher bench_yaml_parse bench_write_latency
EIP2MQTT_BENCH_BUILD="$build" exec python3 "$here/run.py" "$@"
