#!/usr/bin/env bash
# Configures and builds one flavour of eip2mqtt.
#   tools/build.sh [release|asan] [TARGET...]
# (default: release; build dirs build/ and build-asan/; every target unless some are named)
# The asan flavour is one clang build for the sanitized tests and the libFuzzer targets alike:
# its libraries are compiled once, with coverage for the fuzzers, instead of twice. It leaves
# out the suites that only drive the binary: tools/test.sh runs the release build's against it.
set -euo pipefail
cd "$(dirname "$0")/.."
flavour=${1:-release}
shift $(($# > 0 ? 1 : 0))
targets=("$@")
jobs=$(nproc)
case "$flavour" in
  release) dir=build; args=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DEIP2MQTT_WERROR=ON) ;;
  asan) dir=build-asan; args=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_COMPILER=clang++ -DEIP2MQTT_WERROR=ON
    -DEIP2MQTT_SANITIZE=ON -DEIP2MQTT_FUZZ=ON -DEIP2MQTT_BENCH=OFF -DEIP2MQTT_BINARY_SUITES=OFF) ;;
  *) echo "usage: $0 [release|asan]" >&2; exit 2 ;;
esac
cmake -S . -B "$dir" -G Ninja "${args[@]}" >/dev/null
if [ ${#targets[@]} -gt 0 ]; then
  cmake --build "$dir" -j "$jobs" --target "${targets[@]}"
else
  cmake --build "$dir" -j "$jobs"
fi
