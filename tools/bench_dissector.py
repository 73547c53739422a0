#!/usr/bin/env python3
"""tshark's time to decode 100,000 datagrams with the plugin `eip2mqtt dissector` writes,
against its built-in EGD dissector on the same capture, in alternating rounds of one run.

    python3 tools/bench_dissector.py build/eip2mqtt [--rounds 3]

The capture: 1,000 configured exchanges of 4 tags (udint, real, bit, int), 100 datagrams each.
Both runs print one field per frame (`-T fields`): the request id. Prints the median of each
and their ratio; the figures are for information (README "Performance")."""

import argparse
import os
import statistics
import struct
import subprocess
import sys
import tempfile
import time

EXCHANGES = 1000
ROUNDS_OF_DATAGRAMS = 100


def producer(e):
    return (10, 0, e // 250, e % 250 + 1)


def config_text():
    lines = ["gateway:\n  id: bench\nmqtt:\n  url: tcp://127.0.0.1:1883\n  base_topic: b\n",
             "exchanges:\n"]
    for e in range(EXCHANGES):
        lines.append(
            "  - { name: ex%04d, producer_id: %d.%d.%d.%d, exchange_id: %d, length: 12,\n"
            "      period_ms: 100, tags: [ { name: W, address: \"0.0\", type: udint },"
            " { name: R, address: \"4.0\", type: real }, { name: B, address: \"8.3\", type: bit },"
            " { name: I, address: \"10.0\", type: int } ] }\n" % ((e,) + producer(e) + (e + 1,)))
    return "".join(lines)


def write_pcap(path):
    t0_us = 1700000000 * 1000000
    with open(path, "wb") as out:
        out.write(struct.pack("<IHHiIII", 0xA1B2C3D4, 2, 4, 0, 0, 65535, 101))
        for r in range(ROUNDS_OF_DATAGRAMS):
            for e in range(EXCHANGES):
                data = struct.pack("<IfBBh", e * 1000 + r, r * 0.5, 0, 8, -r)
                egd = struct.pack("<BBH4BIIIIII", 0x0D, 1, r + 1, *producer(e), e + 1,
                                  1700000000, 0, 0, 0, 0) + data
                udp = struct.pack(">HHHH", 18246, 18246, 8 + len(egd), 0) + egd
                ip = struct.pack(">BBHHHBBH4B4B", 0x45, 0, 20 + len(udp), 0, 0x4000, 64, 17, 0,
                                 127, 0, 0, 1, 127, 0, 0, 1) + udp
                at = t0_us + (r * EXCHANGES + e) * 100
                out.write(struct.pack("<IIII", at // 1000000, at % 1000000, len(ip), len(ip)))
                out.write(ip)


def timed(argv):
    start = time.monotonic()
    done = subprocess.run(argv, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=True)
    elapsed = time.monotonic() - start
    frames = sum(1 for line in done.stdout.splitlines() if line.strip())
    if frames != EXCHANGES * ROUNDS_OF_DATAGRAMS:
        sys.exit("%s printed %d lines" % (argv, frames))
    return elapsed


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        config = os.path.join(tmp, "plant.yaml")
        plugin = os.path.join(tmp, "eip2mqtt.lua")
        pcap = os.path.join(tmp, "plant.pcap")
        with open(config, "w") as out:
            out.write(config_text())
        subprocess.run([args.binary, "dissector", "-c", config, "-o", plugin], check=True,
                       stdout=subprocess.DEVNULL)
        write_pcap(pcap)
        builtin, generated = [], []
        for _ in range(args.rounds):
            builtin.append(timed(["tshark", "-r", pcap, "-T", "fields", "-e", "egd.rid"]))
            generated.append(timed(["tshark", "-X", "lua_script:" + plugin, "-r", pcap, "-T",
                                    "fields", "-e", "eip2mqtt.request_id"]))
        b, g = statistics.median(builtin), statistics.median(generated)
        print("100,000 datagrams, %d rounds: built-in EGD %.2f s, eip2mqtt plugin %.2f s, "
              "ratio %.2f" % (args.rounds, b, g, g / b))


if __name__ == "__main__":
    main()
