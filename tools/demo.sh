#!/usr/bin/env bash
# The main job on one machine: a local Mosquitto, the bundled simulator producing the consumed
# exchanges of etc/eip2mqtt/eip2mqtt.yaml, and the gateway on that configuration, with a
# subscriber printing the values as they arrive. Ctrl-C stops everything.
#   tools/demo.sh [--seconds N]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=0
if [ "${1:-}" = "--seconds" ]; then seconds=${2:?}; fi

tools/install-deps.sh
# Only what the demo runs (the whole suite is tools/test.sh's job).
tools/build.sh release eip2mqtt

config=etc/eip2mqtt/eip2mqtt.yaml
pids=()
cleanup() {
  # Newest first, each waited for: the gateway publishes `offline` and disconnects cleanly
  # (within its 3 s flush) before the broker it talks to goes away.
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do
    kill "${pids[i]}" 2>/dev/null || true
    wait "${pids[i]}" 2>/dev/null || true
  done
}
trap cleanup EXIT INT TERM

if ! (exec 3<>/dev/tcp/127.0.0.1/1883) 2>/dev/null; then
  echo "== starting Mosquitto on localhost:1883"
  mosquitto -p 1883 >/tmp/eip2mqtt-demo-mosquitto.log 2>&1 &
  pids+=($!)
  for _ in $(seq 50); do (exec 3<>/dev/tcp/127.0.0.1/1883) 2>/dev/null && break; sleep 0.1; done
else
  echo "== using the MQTT broker already on localhost:1883"
fi

echo "== starting the gateway on $config"
build/eip2mqtt run -c "$config" &
pids+=($!)
echo "== starting the simulator"
build/eip2mqtt sim -c "$config" --log-level warn &
pids+=($!)

echo "== values as they arrive (mosquitto_sub -v -t 'acme/demo/#'):"
if [ "$seconds" -gt 0 ]; then
  timeout "$seconds" mosquitto_sub -h 127.0.0.1 -p 1883 -v -t 'acme/demo/#' || true
else
  mosquitto_sub -h 127.0.0.1 -p 1883 -v -t 'acme/demo/#'
fi
