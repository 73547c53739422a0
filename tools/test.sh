#!/usr/bin/env bash
# Runs the whole test suite on a fresh Debian 12 machine: installs what is missing, builds,
# runs every test (unit, integration against a real Mosquitto, interop with tshark) in a normal
# build and again under AddressSanitizer + UndefinedBehaviorSanitizer, checks formatting, and
# validates the example configuration.
set -euo pipefail
cd "$(dirname "$0")/.."

tools/install-deps.sh

echo "== format check"
tools/format.sh --check

echo "== release build and tests"
tools/build.sh release
build/eip2mqtt check -c etc/eip2mqtt/eip2mqtt.yaml >/dev/null
(cd build && ctest --output-on-failure -j "$(nproc)" --timeout 300)

echo "== AddressSanitizer + UBSan build and tests"
tools/build.sh asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tools/lsan.supp
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Not the broker clusters' tests: they measure what ejabberd and RabbitMQ do, minutes of Erlang
# nodes starting; the gateway's side of a move (failover, replay) runs here on Mosquitto.
(cd build-asan && ctest --output-on-failure -j "$(nproc)" --timeout 600 -E '(^|/)Cluster|ClusterPair')

echo "== fuzzing"
tools/fuzz.sh
