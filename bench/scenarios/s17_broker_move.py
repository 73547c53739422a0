"""Scenario 17: the move to the next broker of `mqtt.url`. Two Mosquittos (Debian's defaults)
and one gateway with both in its list; each trial kills the broker the gateway is connected to
(SIGKILL) at T and reads, in the gateway's log, when it said `connected to` the other one, and
the backoff it announced (`reconnecting to ... in N ms`); the killed broker is started again on
its port for the next trial, which kills the other. The target: the backoff plus a round trip
(a loopback one here, well under a millisecond), with a margin of 50 ms for the machine."""

import datetime
import os
import re
import signal
import socket
import time

from benchlib.util import HOST, free_port, median, stop

MARGIN_MS = 50
CONNECTED = re.compile(r"^(\S+ \S+) \S*info\S*: MQTT connected to tcp://[\d.]+:(\d+)")
BACKOFF = re.compile(r"reconnecting to tcp://[\d.]+:\d+ in (\d+) ms")


def log_time(stamp):
    """The gateway's log stamp (local time, milliseconds) as seconds since the epoch."""
    return datetime.datetime.strptime(stamp, "%Y-%m-%d %H:%M:%S.%f").timestamp()


class Move:
    """The gateway of `build` between two brokers of this scenario."""

    def __init__(self, bench, build):
        self.bench, self.build = bench, build
        self.name = "g17" + ("" if build.new else "x")
        self.log = os.path.join(bench.tmp, self.name + ".log")
        self.ports = [free_port(), free_port()]
        for port in self.ports:
            self.start_broker(port)
        urls = ", ".join(f"tcp://{HOST}:{port}" for port in self.ports)
        self.config = bench.write_config(
            self.name, broker_port=self.ports[0], consumed=[(1, 10)], udp_port=free_port(socket.SOCK_DGRAM), build=build,
            log_level="info", mqtt_keys={"url": f"[ {urls} ]"})

    def start_broker(self, port):
        self.bench.spawn_broker(f"move{port}", ["mosquitto", "-p", str(port)], port)

    def connections(self):
        """[(log time, port)] of every `connected to` the gateway logged so far."""
        with open(self.log) as f:
            return [(log_time(m[1]), int(m[2])) for m in map(CONNECTED.match, f) if m]

    def wait_connections(self, count, timeout=15):
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            seen = self.connections()
            if len(seen) >= count:
                return seen
            time.sleep(0.02)
        raise RuntimeError(f"gateway {self.name}: no connection {count} within {timeout} s")

    def trials(self, count):
        """[(ms from the kill to `connected to` the other broker, the backoff announced)]."""
        proc = self.bench.start_gateway(self.name, self.config, build=self.build)
        out = []
        try:
            self.wait_connections(1)
            for i in range(count):
                port = self.connections()[-1][1]
                broker, _ = self.bench.brokers[f"move{port}"]
                killed = time.time()
                broker.send_signal(signal.SIGKILL)
                broker.wait(timeout=5)
                at, moved_to = self.wait_connections(i + 2)[-1]
                if moved_to == port:
                    raise RuntimeError(f"gateway {self.name} connected to the killed broker")
                with open(self.log) as f:
                    backoff = int(BACKOFF.findall(f.read())[-1])
                out.append(((at - killed) * 1000, backoff))
                self.start_broker(port)
        finally:
            stop(proc)
        return out


def run(bench):
    print("[17] the move to the next broker of mqtt.url", flush=True)
    trials = 2 if bench.quick else 8
    rounds = []
    for r in range(bench.rounds):
        rounds.append(bench.per_build(r, lambda build: Move(bench, build).trials(trials)))
    for r, got in enumerate(rounds):
        for build, moves in got.items():
            if moves is not None:
                print(f"    round {r + 1}, {build.label}: " +
                      ", ".join(f"{ms:.0f} ms" for ms, _ in moves), flush=True)
    moves = [m for got in rounds for m in got[bench.build]]
    ms = [m for m, _ in moves]
    backoff = median([b for _, b in moves])
    target = backoff + MARGIN_MS
    bench.row(f"broker move: SIGKILL of the broker in use -> `connected to` the next of "
              f"mqtt.url, ms (two Debian-default Mosquittos, {len(ms)} moves over "
              f"{bench.rounds} rounds)", f"{median(ms):,.0f} (max {max(ms):,.0f})",
              f"{backoff} ms backoff announced", f"{median(ms) / backoff:.2f}",
              f"max <= {target} ms (backoff + {MARGIN_MS})",
              "yes" if max(ms) <= target else "no",
              bench.versus(rounds, lambda got: median([m for m, _ in got])))
