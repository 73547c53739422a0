"""Scenario 9: write latency, a `/set` publication to the first datagram carrying its value,
alone and beside 100 more produced exchanges, against the broker hop itself."""

import socket
import subprocess

from benchlib.util import HOST, free_port, run_json, stop, tool


def write_latency(bench, background, count, build):
    """One produced exchange (p9001) of `build`'s gateway written `count` times at 47
    writes/s, `background` more exchanges produced beside it: write_latency's JSON."""
    port = free_port(socket.SOCK_DGRAM)
    produced = [(9001, 10, 10, f"{HOST}:{port}")]
    sink = None
    if background:
        # The background exchanges go to a sink that reads them, so that no kernel buffer
        # fills and no send fails.
        bport = free_port(socket.SOCK_DGRAM)
        sink = bench.start_sink(bport, "--duration", count / 47 + 20, stdout=subprocess.DEVNULL)
        produced += [(9100 + i, 10, 10, f"{HOST}:{bport}") for i in range(background)]
    name = f"g9b{background}"
    config = bench.write_config(name, produced=produced, udp_port=free_port(socket.SOCK_DGRAM),
                                build=build)
    try:
        gw = bench.start_gateway(name, config, build=build)
        bench.wait_online(name, proc=gw, build=build)
    except Exception:
        stop(sink)
        raise
    got = run_json([tool("write_latency"), "--port", str(bench.broker_port), "--udp-port",
                    str(port), "--topic", "b/p9001/t1/set", "--exchange-id", "9001",
                    "--offset", "8", "--rate", "47", "--count", str(count),
                    "--id", f"bench-writer-{background}"], timeout=count / 47 + 60)
    stop(gw)
    stop(sink)
    return got


def run(bench):
    print("[9] write latency: MQTT /set -> the datagram carrying it (10 ms period)", flush=True)
    count = 50 if bench.quick else 500  # at 47 writes/s: ~1 s or ~11 s
    for background in (0, 100):
        def one(build):
            got = write_latency(bench, background, count, build)
            print(f"    {build.label}, {1 + background} produced exchange(s): {got}", flush=True)
            return got

        runs = bench.per_build(0, one)
        got = runs[bench.build]
        complete = got["seen"] == got["writes"] == got["results_ok"]
        if not complete:
            bench.notes.append(f"scenario 9 ({1 + background} exchanges): {got['writes']} "
                               f"writes, {got['seen']} seen on the wire, "
                               f"{got['results_ok']} ok results")
        what = "1 exchange" if not background else f"1 + {background} exchanges"
        bench.row(f"write latency /set -> datagram p99 (ms), {what} at 10 ms",
                  f"{got['p99_ms']:.2f} (p50 {got['p50_ms']:.2f}, max {got['max_ms']:.2f}; "
                  f"{got['seen']}/{got['writes']} seen, {got['results_ok']} ok results)",
                  f"{got['hop_p99_ms']:.2f} (MQTT hop p99: /set publish -> a subscriber)",
                  "-", "<= 11 ms (period + 1 ms)",
                  "yes" if got["p99_ms"] <= 11 and complete else "no",
                  bench.versus([runs], lambda g: g["p99_ms"], fmt="{:.2f}".format))
