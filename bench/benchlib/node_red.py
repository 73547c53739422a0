"""The peer a user would build instead of the gateway: a Node-RED flow (bench/peers/node-red/:
`udp in` -> one `function` decoding the datagram -> `mqtt out`, MQTT 3.1.1), run headless from
the npm install tools/install-deps.sh makes. One process per NodeRed, in a user directory of
its own; ready once a probe datagram it decoded has reached the broker."""

import json
import os
import socket
import struct
import subprocess
import tempfile
import time

from benchlib.util import BENCH_DIR, HOST, free_port, stop

PEER_DIR = os.path.join(BENCH_DIR, "peers", "node-red")
NODE_RED = os.path.join(PEER_DIR, "node_modules", ".bin", "node-red")
FLOW = os.path.join(PEER_DIR, "flow.json")
SETTINGS = os.path.join(PEER_DIR, "settings.js")
# The flow answers a datagram of exchange 0 with one message on BASE/_peer/node-red/ready: a
# topic of four levels, which no counter on BASE/+/+ counts.
READY_TOPIC = "_peer/node-red/ready"


def require_installed():
    """Fails loudly where Node-RED is not installed: the peer row is part of the run."""
    if not os.access(NODE_RED, os.X_OK):
        raise SystemExit(f"missing {NODE_RED}: run tools/install-deps.sh (it installs Node-RED "
                         "from bench/peers/node-red/package-lock.json with npm ci)")


def version():
    with open(os.path.join(PEER_DIR, "node_modules", "node-red", "package.json")) as f:
        return json.load(f)["version"]


def probe_datagram():
    """A datagram of exchange 0 (docs/protocol.md: 32-byte header, then the data)."""
    header = bytearray(32)
    header[0], header[1] = 0x0D, 0x01
    struct.pack_into("<I", header, 8, 0)
    return bytes(header) + bytes(8)


class NodeRed:
    """Node-RED running the peer flow: datagrams to `udp_port`, one message per tag on
    `{base}/e{exchange}/{ts|tK}` at `qos` to the broker on `broker_port`."""

    def __init__(self, broker_port, qos, base="n", log_dir=None):
        self.broker_port = broker_port
        self.qos = qos
        self.base = base
        self.udp_port = free_port(socket.SOCK_DGRAM)
        self.user_dir = tempfile.mkdtemp(prefix="eip2mqtt-node-red-", dir=log_dir)
        self.log_path = os.path.join(self.user_dir, "node-red.log")
        self.proc = None

    @property
    def pid(self):
        return self.proc.pid

    def start(self, timeout=90):
        """Starts Node-RED and returns once it is ready (bounded by `timeout` s): its flow
        started, its UDP port bound and its MQTT connection up, as a probe datagram decoded
        and published to the broker shows."""
        require_installed()
        env = dict(os.environ, EIP2MQTT_PEER_UDP_PORT=str(self.udp_port),
                   EIP2MQTT_PEER_BROKER_PORT=str(self.broker_port),
                   EIP2MQTT_PEER_QOS=str(self.qos), EIP2MQTT_PEER_BASE=self.base,
                   EIP2MQTT_PEER_UI_PORT=str(free_port()))
        log = open(self.log_path, "w")
        self.proc = subprocess.Popen([NODE_RED, "--settings", SETTINGS, "--userDir",
                                      self.user_dir, FLOW], stdout=log, stderr=log, env=env)
        log.close()
        sub = subprocess.Popen(["mosquitto_sub", "-h", HOST, "-p", str(self.broker_port),
                                "-C", "1", "-W", str(timeout), "-t",
                                f"{self.base}/{READY_TOPIC}"],
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        deadline = time.monotonic() + timeout
        try:
            with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
                while sub.poll() is None and self.proc.poll() is None and \
                        time.monotonic() < deadline:
                    s.sendto(probe_datagram(), (HOST, self.udp_port))
                    time.sleep(0.1)
            out = sub.communicate(timeout=5)[0] if sub.poll() is not None else ""
        finally:
            stop(sub)
        if out.strip() != "ready":
            self.stop()
            raise RuntimeError(f"Node-RED did not become ready in {timeout} s: {self.log_tail()}")
        return self

    def log_tail(self):
        with open(self.log_path, errors="replace") as f:
            return " / ".join(line.strip() for line in f.readlines()[-5:])

    def stop(self):
        stop(self.proc)
