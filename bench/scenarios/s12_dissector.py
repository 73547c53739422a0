"""Scenario 12: tshark's time to decode a capture of 1,000 exchanges with the plugin
`eip2mqtt dissector` writes, against Wireshark's built-in EGD dissector on the same capture in
the same round (for information: the plugin decodes every tag, the built-in one only the
header). Each decoder evaluates a display filter, so that tshark dissects every datagram."""

import os
import socket
import struct
import subprocess
import time

from benchlib.builds import NotInBuild
from benchlib.config import write_config
from benchlib.util import consumed_list

EXCHANGES, TAGS = 1000, 4
PORT = 18246


def datagram(exchange_id, request_id):
    """A data datagram of write_config's consumed layout: producer 10.0.0.1, lint ts at 0,
    then dints; t1 carries the request id."""
    header = struct.pack("<BBH4sIIIIHHI", 0x0D, 1, request_id & 0xFFFF,
                         socket.inet_aton("10.0.0.1"), exchange_id, 1700000000, 0, 0, 0, 0, 0)
    data = struct.pack("<q", request_id) + struct.pack("<i", request_id) + bytes(4 * (TAGS - 2))
    return header + data


def frame(payload):
    """Ethernet, IPv4 and UDP around `payload`, 10.0.0.1 to 10.0.0.255 (checksums 0)."""
    udp = struct.pack("!HHHH", PORT, PORT, 8 + len(payload), 0) + payload
    ip = struct.pack("!BBHHHBBH4s4s", 0x45, 0, 20 + len(udp), 0, 0, 64, 17, 0,
                     socket.inet_aton("10.0.0.1"), socket.inet_aton("10.0.0.255")) + udp
    return b"\xff" * 6 + b"\x02\x00\x00\x00\x00\x01" + b"\x08\x00" + ip


def write_capture(path, rounds):
    """`rounds` x EXCHANGES datagrams, one every 100 us, in the classic pcap format."""
    with open(path, "wb") as f:
        f.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 1))
        for r in range(rounds):
            for e in range(1, EXCHANGES + 1):
                packet = frame(datagram(e, r + 1))
                micros = (r * EXCHANGES + e) * 100
                f.write(struct.pack("<IIII", 1700000000 + micros // 1000000, micros % 1000000,
                                    len(packet), len(packet)))
                f.write(packet)


def tshark_seconds(args):
    start = time.monotonic()
    out = subprocess.run(["tshark"] + args, capture_output=True, text=True, timeout=1200)
    elapsed = time.monotonic() - start
    if out.returncode != 0:
        raise RuntimeError(f"tshark {' '.join(args)} exited {out.returncode}: "
                           f"{out.stderr.strip()[:500]}")
    return elapsed, out.stdout.count("\n")


def plugin_of(bench, build):
    config = write_config(bench.tmp, "g12", 1, consumed=consumed_list(EXCHANGES, TAGS),
                          udp_port=PORT)
    plugin = os.path.join(bench.tmp, f"g12-{'new' if build.new else 'old'}.lua")
    out = subprocess.run([build.gateway, "dissector", "-c", config, "-o", plugin],
                         capture_output=True, text=True, timeout=120)
    if out.returncode != 0:
        if build.new:
            raise RuntimeError(f"dissector exited {out.returncode}: {out.stderr.strip()}")
        raise NotInBuild(build, (out.stderr.strip().splitlines() or ["no dissector"])[0])
    return plugin


def measure_round(bench, capture, rounds, build, round_index):
    """(plugin s, built-in s), in an order that alternates by round."""
    plugin = plugin_of(bench, build)
    # Exchange 500's datagram of the last round: one line from each decoder.
    runs = {
        "plugin": ["-r", capture, "-X", f"lua_script:{plugin}", "-Y",
                   f"eip2mqtt.e500.t1 == {rounds}"],
        "built-in": ["-r", capture, "-Y", f"egd.exid == 500 && egd.rid == {rounds}"],
    }
    order = ("plugin", "built-in") if round_index % 2 == 0 else ("built-in", "plugin")
    got = {}
    for name in order:
        got[name], lines = tshark_seconds(runs[name])
        if lines != 1:
            raise RuntimeError(f"tshark with the {name} dissector matched {lines} datagrams, "
                               f"not 1")
    print(f"    round {round_index + 1}: plugin {got['plugin']:.2f} s, built-in "
          f"{got['built-in']:.2f} s ({build.label})", flush=True)
    return got["plugin"], got["built-in"]


def run(bench):
    print("[12] tshark with the generated dissector against the built-in one", flush=True)
    rounds = 10 if bench.quick else 100
    capture = os.path.join(bench.tmp, "g12.pcap")
    write_capture(capture, rounds)
    results = [bench.per_build(r, lambda b, r=r: measure_round(bench, capture, rounds, b, r))
               for r in range(bench.rounds)]
    pairs = [r[bench.build] for r in results]
    ratios = [p / b for p, b in pairs]
    middle = sorted(range(len(pairs)), key=lambda i: ratios[i])[len(pairs) // 2]
    note = (" (rounds: " + ", ".join(f"{x:.1f}" for x in ratios) + ")") if len(ratios) > 1 else ""
    bench.row(f"s for tshark to decode {rounds * EXCHANGES:,} datagrams of {EXCHANGES:,} "
              f"exchanges x {TAGS} tags with the generated plugin{bench.rounds_label()}",
              f"{pairs[middle][0]:.2f}", f"{pairs[middle][1]:.2f} (built-in EGD dissector)",
              f"{ratios[middle]:.1f}{note}", "- (for information)", "-",
              bench.versus(results, lambda p: p[0], fmt="{:.2f}".format))
