#!/usr/bin/env bash
# Installs the Debian 12 packages eip2mqtt builds, runs and tests with, and the npm package of one
# test tool. Idempotent: installs only what is missing, and runs apt-get update only when
# something is.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libboost-dev libpaho-mqttpp-dev libpaho-mqtt-dev nlohmann-json3-dev libyaml-cpp-dev
  libspdlog-dev libfmt-dev libcli11-dev libsystemd-dev prometheus-cpp-dev libmosquitto-dev
  libprotobuf-dev protobuf-compiler libsqlite3-dev libpcap-dev
  libgtest-dev libgmock-dev
  mosquitto mosquitto-clients
  clang libclang-rt-14-dev tshark systemd openssl iproute2 iptables
  python3 python3-jsonschema nodejs
  lintian stress-ng
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Eclipse Tahu's Sparkplug B payload library, from npm, for the tests that decode what the
# gateway publishes with an implementation we did not write (versions pinned by its lock file).
tahu="$(cd "$(dirname "$0")/.." && pwd)/tests/support/tahu"
if [ ! -d "$tahu/node_modules/sparkplug-payload" ]; then
  if ! command -v npm >/dev/null; then
    "${sudo_cmd[@]}" apt-get update -qq
    "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends npm
  fi
  npm ci --prefix "$tahu" --no-audit --no-fund --ignore-scripts --loglevel=error
fi
