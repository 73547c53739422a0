"""What scenario 13 hears of a hot-standby pair: the produced datagrams, each with its kernel
receive time and source port (each unit sends from an ephemeral port of its own), and the MQTT
messages of some topics, each with mosquitto_sub's receive time; and a probe publisher beside
them, for the broker's round trip. One process reads it all, without threads: every wait of
the scenario is a `pump` of bounded length."""

import json
import os
import selectors
import socket
import struct
import subprocess
import time

from benchlib.util import HOST, stop

# Linux's SO_TIMESTAMPNS (Python's socket module does not name it): the kernel's receive time
# of each datagram, CLOCK_REALTIME like the instants the scenario records.
SO_TIMESTAMPNS = getattr(socket, "SO_TIMESTAMPNS", 35)
PROBE = "b/_bench/probe"


def wall_ns(stamp):
    """mosquitto_sub's `%U` (seconds.nanoseconds) in ns."""
    seconds, _, fraction = stamp.partition(".")
    return int(seconds) * 1_000_000_000 + int(fraction.ljust(9, "0")[:9])


class PairWatch:
    def __init__(self, bench, topics):
        """A UDP socket on a free port (`port`), and a subscriber of `topics` on the broker in
        use, subscribed once the first probe came back."""
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, SO_TIMESTAMPNS, 1)
        self.sock.bind((HOST, 0))
        self.sock.setblocking(False)
        self.port = self.sock.getsockname()[1]
        broker = ["-h", HOST, "-p", str(bench.broker_port)]
        filters = [arg for topic in list(topics) + [PROBE] for arg in ("-t", topic)]
        self.sub = subprocess.Popen(["mosquitto_sub", *broker, "-i", "bench-pair-watch", "-F",
                                     "%U %t %p", *filters], stdout=subprocess.PIPE,
                                    stderr=subprocess.DEVNULL)
        self.pub = subprocess.Popen(["mosquitto_pub", *broker, "-i", "bench-pair-probe", "-q",
                                     "1", "-t", PROBE, "-l"], stdin=subprocess.PIPE,
                                    stderr=subprocess.DEVNULL, text=True)
        bench.procs += [self.sub, self.pub]
        os.set_blocking(self.sub.stdout.fileno(), False)
        self.selector = selectors.DefaultSelector()
        self.selector.register(self.sock, selectors.EVENT_READ)
        self.selector.register(self.sub.stdout, selectors.EVENT_READ)
        self.datagrams = []  # (kernel receive ns, source port)
        self.messages = []  # (receive ns, topic, payload)
        self.latest = {}  # topic -> its latest (receive ns, payload)
        self.partial = b""
        self.round_trips = []
        try:
            self.until(self.probe_back, 10, "the probe subscriber to hear its first probe",
                       every=self.send_probe, every_s=0.5)
            self.round_trips.clear()  # that one waited for the subscription
        except Exception:
            self.close()
            raise

    def close(self):
        self.selector.close()
        self.sock.close()
        if self.pub.stdin:
            self.pub.stdin.close()
        stop(self.pub)
        stop(self.sub)

    def pump(self, seconds):
        """Reads what arrives within `seconds` (returns at the first arrival)."""
        for key, _ in self.selector.select(max(0.0, seconds)):
            if key.fileobj is self.sock:
                self.read_datagrams()
            else:
                self.read_messages()

    def until(self, done, timeout, what, every=None, every_s=0.0):
        """done()'s first true value, pumping meanwhile; `every()` each `every_s` seconds.
        RuntimeError after `timeout` seconds."""
        deadline = time.monotonic() + timeout
        next_every = time.monotonic()
        while True:
            if every and time.monotonic() >= next_every:
                every()
                next_every = time.monotonic() + every_s
            got = done()
            if got:
                return got
            left = deadline - time.monotonic()
            if left <= 0:
                raise RuntimeError(f"no {what} within {timeout:.0f} s")
            self.pump(min(left, 0.05))

    def run_for(self, seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            self.pump(deadline - time.monotonic())

    def read_datagrams(self):
        while True:
            try:
                _, ancillary, _, source = self.sock.recvmsg(2048, socket.CMSG_SPACE(16))
            except BlockingIOError:
                return
            received = time.time_ns()
            for level, kind, data in ancillary:
                if level == socket.SOL_SOCKET and kind == SO_TIMESTAMPNS:
                    seconds, nanos = struct.unpack("qq", data[:16])
                    received = seconds * 1_000_000_000 + nanos
            self.datagrams.append((received, source[1]))

    def read_messages(self):
        try:
            chunk = os.read(self.sub.stdout.fileno(), 65536)
        except BlockingIOError:
            return
        if not chunk:
            self.selector.unregister(self.sub.stdout)
            raise RuntimeError("mosquitto_sub ended")
        *lines, self.partial = (self.partial + chunk).split(b"\n")
        for line in lines:
            stamp, topic, payload = (line.decode(errors="replace").split(" ", 2) + [""])[:3]
            received = wall_ns(stamp)
            self.messages.append((received, topic, payload))
            self.latest[topic] = (received, payload)
            if topic == PROBE and payload.isdigit():
                self.round_trips.append((received - int(payload)) / 1e6)

    def send_probe(self):
        """Publishes a probe stamped now (CLOCK_REALTIME ns): its round trip is counted when
        it comes back."""
        self.pub.stdin.write(f"{time.time_ns()}\n")
        self.pub.stdin.flush()

    def probe_back(self):
        return bool(self.round_trips)

    def probe(self, timeout=10):
        """One publish -> receive round trip through the broker, ms."""
        count = len(self.round_trips)
        self.send_probe()
        self.until(lambda: len(self.round_trips) > count, timeout, "probe back")
        return self.round_trips[-1]

    def first_message(self, since, match):
        """The first message from index `since` on for which match(topic, payload) holds:
        (receive ns, topic, payload), or None."""
        return next((m for m in self.messages[since:] if match(m[1], m[2])), None)

    def first_datagram(self, since, match):
        return next((d for d in self.datagrams[since:] if match(*d)), None)


def json_field(payload, key):
    """`key` of a JSON object payload, or None (an empty retained message, say)."""
    try:
        value = json.loads(payload)
    except ValueError:
        return None
    return value.get(key) if isinstance(value, dict) else None
