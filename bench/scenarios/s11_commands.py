"""Scenario 11: the command responder on its own UDP port. How many requests a second it answers
with none lost, its rate limit set out of the way; and what a flood of requests at ten times the
default limit costs the data path, whose zero-loss datagram rate is measured with and without
the flood in alternating rounds."""

import socket
import struct
import threading
import time

from benchlib.util import HOST, consumed_list, free_port, median, stop
from scenarios.s01_udp import accepted_trial

# Above any rate the requester reaches: the responder's own ceiling, not its limit, shows.
UNLIMITED = 100000
# The default `max_requests_per_s`, and the flood: ten times it.
DEFAULT_LIMIT, FLOOD_FACTOR = 100, 10


def summary_request(request_id):
    """A Summary request from index 0 (PDU type 7, version 1, 12 bytes)."""
    return struct.pack("<BBHBBH", 7, 0, request_id & 0xFFFF, 1, 0, 12) + bytes(4)


def commands_port():
    return free_port(socket.SOCK_DGRAM)


class Requester:
    """Sends Summary requests at `rate`/s for `duration` s and counts the answers."""

    def __init__(self, port):
        self.port = port
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4 << 20)
        self.sock.bind((HOST, 0))
        self.sock.settimeout(0.2)
        self.answers = 0
        self.done = threading.Event()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self):
        while not self.done.is_set():
            try:
                data = self.sock.recv(2048)
            except socket.timeout:
                continue
            if data and data[0] == 8:  # Summary response
                self.answers += 1

    def send(self, rate, duration, stop_event=None):
        """Paced in 1 ms slices; returns (sent, rate achieved)."""
        sent, start = 0, time.monotonic()
        while time.monotonic() - start < duration:
            if stop_event is not None and stop_event.is_set():
                break
            due = int((time.monotonic() - start) * rate) + 1
            while sent < due:
                self.sock.sendto(summary_request(sent), (HOST, self.port))
                sent += 1
            time.sleep(0.001)
        elapsed = time.monotonic() - start
        return sent, sent / elapsed if elapsed else 0

    def close(self, settle=0.5):
        """Waits (bounded) for the last answers, then stops reading."""
        time.sleep(settle)
        self.done.set()
        self.reader.join(timeout=2)
        self.sock.close()


def commands_config(port, limit):
    # The requester is trusted (docs/protocol.md section 9.7: answered in full without proving
    # its address) and its own limit is the overall one: the responder's work, not the proof's
    # round trip, is measured.
    return {"enabled": "true", "port": port, "max_requests_per_s": limit,
            "max_requests_per_s_per_source": limit, "allow": f"[{HOST}/32]",
            "trusted": f"[{HOST}/32]"}


def answered_row(bench, duration, steps):
    """The zero-loss rate of answered requests, the limit set to UNLIMITED, in paired rounds:
    a single ramp is decided by whether one step loses a few requests or none."""
    def measure(build):
        port = commands_port()
        gw, _ = bench.launch_gateway("g11a", consumed_list(16), 1, build=build,
                                     commands=commands_config(port, UNLIMITED))

        def trial(rate, n):
            requester = Requester(port)
            sent, achieved = requester.send(rate, duration)
            requester.close()
            print(f"    requests  {rate:9.0f}/s: sent {sent} answered {requester.answers} "
                  f"({achieved:.0f}/s; {build.label})", flush=True)
            return requester.answers == sent, achieved

        rate = bench.zero_loss_ceiling(trial, steps, 2000, "scenario 11")[0]
        stop(gw)
        return rate

    rounds = [bench.per_build(r, measure) for r in range(bench.rounds)]
    rates = [r[bench.build] for r in rounds]
    bench.row("command requests/s answered, zero loss (Summary, 16 exchanges configured, "
              f"max_requests_per_s {UNLIMITED:,}){bench.rounds_label()}",
              f"{median(rates):,.0f}{bench.values_note(rates)}", "-", "-", "-", "-",
              bench.versus(rounds, lambda r: r))


def data_ceiling(bench, duration, steps, build, flood):
    """The gateway's zero-loss datagram rate (16 exchanges of 100 tags, as scenario 1), with
    or without a requester flooding the command port at FLOOD_FACTOR x the default limit."""
    name = "g11f"
    port = commands_port()
    gw, udp_port = bench.launch_gateway(name, consumed_list(16), 1, build=build,
                                        commands=commands_config(port, DEFAULT_LIMIT))
    stop_flood = threading.Event()
    flooder = Requester(port) if flood else None
    thread = None
    if flood:
        thread = threading.Thread(target=flooder.send, daemon=True,
                                  args=(DEFAULT_LIMIT * FLOOD_FACTOR, 600, stop_flood))
        thread.start()
    try:
        trial = accepted_trial(bench, name, udp_port, 1, 100, duration, build)
        rate = bench.zero_loss_ceiling(trial, steps, 25000, "scenario 11")[0]
    finally:
        stop_flood.set()
        if thread:
            thread.join(timeout=5)
            flooder.close(settle=0)
        stop(gw)
    return rate


def flood_pair(bench, duration, steps, build, round_index):
    """(with the flood, without it) for `build`, in an order that alternates by round."""
    order = (False, True) if round_index % 2 == 0 else (True, False)
    got = {flood: data_ceiling(bench, duration, steps, build, flood) for flood in order}
    print(f"    round {round_index + 1}: {got[True]:,.0f} with the flood, {got[False]:,.0f} "
          f"without ({build.label})", flush=True)
    return got[True], got[False]


def flood_row(bench, duration, steps):
    rounds = [bench.per_build(r, lambda b, r=r: flood_pair(bench, duration, steps, b, r))
              for r in range(bench.rounds)]
    pairs = [r[bench.build] for r in rounds]
    ratios = [w / wo if wo else 0 for w, wo in pairs]
    middle = sorted(range(len(pairs)), key=lambda i: ratios[i])[len(pairs) // 2]
    note = (" (rounds: " + ", ".join(f"{x:.2f}" for x in ratios) + ")") if len(ratios) > 1 else ""
    bench.row(f"datagrams/s accepted, zero loss, command port flooded at {FLOOD_FACTOR} x its "
              f"limit ({DEFAULT_LIMIT * FLOOD_FACTOR:,} requests/s){bench.rounds_label()}",
              f"{pairs[middle][0]:,.0f}", f"{pairs[middle][1]:,.0f} (the same gateway, no flood)",
              f"{ratios[middle]:.2f}{note}", ">= 0.95", "yes" if ratios[middle] >= 0.95 else "no",
              bench.versus(rounds, lambda p: p[0]))


def run(bench):
    print("[11] the command responder: requests answered, and the data path under a flood",
          flush=True)
    duration = 1 if bench.quick else 2
    steps = 1 if bench.quick else 3
    answered_row(bench, duration, steps)
    flood_row(bench, duration, steps)
