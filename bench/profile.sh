#!/usr/bin/env bash
# Profiles the gateway under a steady load (bench/results/profile.md): a private Mosquitto on a
# free port, the gateway (build-bench/, as bench/run.sh builds it) consuming 10 exchanges x 100
# tags, mqtt_counter subscribed, load_generator sending; with `perf`, `perf record -g` of the
# gateway for the load's duration. Prints the generator's and the counter's JSON and the
# gateway's CPU time per publication. Everything runs on 127.0.0.1 and stops by itself.
#   bench/profile.sh QOS CHANGE RATE SECONDS [perf]     e.g. bench/profile.sh 0 0.1 9000 5 perf
# The perf data is left in $EIP2MQTT_PROFILE_DIR (default: a new temporary directory, printed);
# $EIP2MQTT_PROFILE_CALLGRAPH replaces perf's `-g` (e.g. "--call-graph dwarf,8192");
# $EIP2MQTT_PROFILE_SHAPE the exchanges x tags (default 10x100; 100x10 as in the bench's rows).
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,10p' "$0" >&2
  exit 2
fi
qos=$1 change=$2 rate=$3 seconds=$4 perf=${5:-}
shape="${EIP2MQTT_PROFILE_SHAPE:-10x100}"
exchanges="${shape%x*}" tags="${shape#*x}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${EIP2MQTT_BENCH_BUILD:-$(dirname "$here")/build-bench}"
work="${EIP2MQTT_PROFILE_DIR:-$(mktemp -d /tmp/eip2mqtt-profile-XXXXXX)}"
mkdir -p "$work/state"
free_port() {
  python3 -c "import socket,sys;s=socket.socket(socket.AF_INET,getattr(socket,sys.argv[1]));s.bind(('127.0.0.1',0));print(s.getsockname()[1])" "$1"
}
broker_port=$(free_port SOCK_STREAM)
udp_port=$(free_port SOCK_DGRAM)
pids=()
cleanup() { for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT

cat >"$work/mosquitto.conf" <<EOC
listener $broker_port 127.0.0.1
allow_anonymous true
persistence false
log_dest none
set_tcp_nodelay true
max_inflight_messages 1000
max_queued_messages 1000000
max_queued_bytes 0
EOC
mosquitto -c "$work/mosquitto.conf" &
pids+=($!)

python3 - "$broker_port" "$udp_port" "$qos" "$work/state" "$exchanges" "$tags" \
  >"$work/gateway.yaml" <<'PY'
import sys
broker, udp, qos, state = sys.argv[1:5]
exchanges, tags = int(sys.argv[5]), int(sys.argv[6])
print(f"gateway: {{ id: gp, state_dir: {state}, log_level: warn }}\nmqtt:\n"
      f"  url: tcp://127.0.0.1:{broker}\n  qos: {qos}\n  retain: false\n  metrics_interval_s: 1\n"
      f"eip: {{ bind: 127.0.0.1, port: {udp} }}\nexchanges:")
for i in range(1, exchanges + 1):
    print(f"  - name: e{i}\n    direction: consume\n    producer_id: 10.0.0.1\n"
          f"    exchange_id: {i}\n    length: {8 + 4 * (tags - 1)}\n    period_ms: 1000\n"
          f"    timeout_ms: 0\n"
          f"    topic: e{i}\n    tags:")
    print('      - { name: ts, address: "0.0", type: lint }')
    for t in range(1, tags):
        print(f'      - {{ name: t{t}, address: "{8 + 4 * (t - 1)}.0", type: dint }}')
PY
"$build/eip2mqtt" run -c "$work/gateway.yaml" 2>"$work/gateway.log" &
gateway=$!
pids+=($gateway)
"$build/bench/mqtt_counter" --port "$broker_port" --filter 'eip2mqtt/+/+' --qos "$qos" \
  --max-s 60 --idle-ms 1500 --ready-file "$work/ready" --id profile >"$work/counter.json" &
counter=$!
pids+=($counter)
for _ in $(seq 100); do [ -f "$work/ready" ] && break; sleep 0.05; done
[ -f "$work/ready" ] || { echo "the subscriber never connected" >&2; exit 1; }
sleep 0.5  # the gateway's first connection and retained publications settle
if [ -n "$perf" ]; then
  perf record -F 999 ${EIP2MQTT_PROFILE_CALLGRAPH:--g} -p "$gateway" -o "$work/perf.data" -- sleep "$seconds" >/dev/null 2>&1 &
  recorder=$!
fi
"$build/bench/load_generator" --port "$udp_port" --exchanges "$exchanges" --tags "$tags" \
  --rate "$rate" --duration "$seconds" --change "$change" >"$work/generator.json"
[ -n "$perf" ] && wait "$recorder"
wait "$counter"
ticks=$(awk '{print $14 + $15}' "/proc/$gateway/stat")
messages=$(grep -o '"messages":[0-9]*' "$work/counter.json" | cut -d: -f2)
echo "generator: $(cat "$work/generator.json")"
echo "counter: $(cat "$work/counter.json")"
python3 -c "import sys; t, m = map(int, sys.argv[1:]); print(f'gateway CPU per publication: {t * 10000 / max(1, m):.2f} us ({t} ticks, {m} publications)')" "$ticks" "${messages:-0}"
[ -n "$perf" ] && echo "perf data: $work/perf.data (perf report -i $work/perf.data --sort comm,symbol)"
exit 0
