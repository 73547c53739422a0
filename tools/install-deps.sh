#!/usr/bin/env bash
# Installs the Debian 12 packages eip2mqtt builds, runs and tests with, and the npm packages of
# two test tools and of the benchmark's Node-RED peer. Idempotent: installs only what is missing,
# and runs apt-get update only when something is.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config clang-format
  libboost-dev libpaho-mqttpp-dev libpaho-mqtt-dev nlohmann-json3-dev libyaml-cpp-dev
  libspdlog-dev libfmt-dev libcli11-dev libsystemd-dev prometheus-cpp-dev libmosquitto-dev
  libprotobuf-dev protobuf-compiler libsqlite3-dev libpcap-dev libssl-dev
  libgtest-dev libgmock-dev
  mosquitto mosquitto-clients
  clang libclang-rt-14-dev tshark systemd openssl iproute2 iptables
  python3 python3-jsonschema nodejs universal-ctags
  lintian stress-ng chromium
  ejabberd rabbitmq-server
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
# ejabberd and RabbitMQ are broker clusters for the tests, which start their own nodes on free
# ports (tests/support/broker_cluster.hpp): the system's own services, which Debian starts on
# install, are not used, so they are stopped and kept off.
for service in ejabberd rabbitmq-server; do
  if command -v systemctl >/dev/null && systemctl is-enabled --quiet "$service" 2>/dev/null; then
    "${sudo_cmd[@]}" systemctl disable --now --quiet "$service" 2>/dev/null || true
  fi
done

# Eclipse Tahu's Sparkplug B payload library, from npm, for the tests that decode what the
# gateway publishes with an implementation we did not write (versions pinned by its lock file).
root="$(cd "$(dirname "$0")/.." && pwd)"
need_npm() {
  if ! command -v npm >/dev/null; then
    "${sudo_cmd[@]}" apt-get update -qq
    "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends npm
  fi
}
tahu="$root/tests/support/tahu"
if [ ! -d "$tahu/node_modules/sparkplug-payload" ]; then
  need_npm
  npm ci --prefix "$tahu" --no-audit --no-fund --ignore-scripts --loglevel=error
fi

# puppeteer-core, for the status page's browser test: it drives Debian's chromium (no browser
# of its own is downloaded; versions pinned by its lock file).
browser="$root/tests/support/browser"
if [ ! -d "$browser/node_modules/puppeteer-core" ]; then
  need_npm
  npm ci --prefix "$browser" --no-audit --no-fund --ignore-scripts --loglevel=error
fi

# Node-RED, for the benchmark's peer row (bench/README.md, scenario 14): the flow a user would
# build instead of the gateway, pinned by bench/peers/node-red/package.json and its lock file.
# Reinstalled when package.json pins another version than the one installed.
node_red="$root/bench/peers/node-red"
wanted="$(sed -n 's/^ *"node-red": "\([0-9.]*\)".*/\1/p' "$node_red/package.json")"
installed="$(sed -n 's/^ *"version": "\([^"]*\)".*/\1/p' \
  "$node_red/node_modules/node-red/package.json" 2>/dev/null | head -1 || true)"
if [ "$installed" != "$wanted" ]; then
  need_npm
  npm ci --prefix "$node_red" --no-audit --no-fund --ignore-scripts --loglevel=error
fi
