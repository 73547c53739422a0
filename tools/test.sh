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
(cd build-asan && ctest --output-on-failure -j "$(nproc)" --timeout 600)
# The suites that only drive the binary (integration, conformance, interop), built once by the
# release build, against the sanitized binary. Not the package's tests (a sanitized binary is
# never packaged) nor the broker clusters' (they measure what ejabberd and RabbitMQ do, minutes
# of Erlang nodes starting; the gateway's side of a move, failover and replay, runs on Mosquitto).
(cd build && EIP2MQTT_TEST_BINARY="$PWD/../build-asan/eip2mqtt" ctest --output-on-failure \
  -j "$(nproc)" --timeout 600 -L '^(integration|conformance|interop)_tests$' \
  -E '^PackageTest\.|(^|/)Cluster|ClusterPair')

echo "== fuzzing"
tools/fuzz.sh
