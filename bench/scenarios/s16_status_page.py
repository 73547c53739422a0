"""Scenario 16: what the status page costs the data path, and how soon it shows a large plant.
The zero-loss datagram rate (scenario 1's search) and the per-tag publication rate (scenario 2's
run, QoS 1, every tag changing) of a gateway with its listener on, with 10 browsers' event
streams open against none, in paired rounds; then the time the page takes, in headless
chromium, to show its exchanges and an open exchange's tags with 1,000 x 100 tags, against the
same page with 1 x 100."""

import http.client
import os

from benchlib.builds import NotInBuild
from benchlib.event_streams import EventStreams
from benchlib.util import (BENCH_DIR, HOST, consumed_list, free_port, median, ratio_text,
                           run_json, stop)
from scenarios.s01_udp import accepted_trial

STREAMS = 10  # browsers watching
WATCHED = f"status page, {STREAMS} event streams open against none: "
CHROMIUM = "/usr/bin/chromium"
RENDER = os.path.join(BENCH_DIR, "page_render.js")
PUPPETEER = os.path.join(os.path.dirname(BENCH_DIR), "tests", "support", "browser", "node_modules",
                         "puppeteer-core")


def ceiling(bench, duration, steps, watched, build):
    """Scenario 1's zero-loss search on `build`'s gateway of 16 exchanges (each trial sends to
    the next), its listener on, with the event streams open when `watched` (each stream opens
    of the exchanges the trials send to)."""
    name = "g16w" if watched else "g16"
    port = free_port()
    gw, udp_port = bench.launch_gateway(name, consumed_list(16), 1, build=build,
                                        prometheus=port)
    try:
        trial = accepted_trial(bench, name, udp_port, 1, 100, duration, build)
        if not watched:
            return bench.zero_loss_ceiling(trial, steps, 25000, "scenario 16")[0]
        with EventStreams(port, [f"e{n}" for n in range(1, STREAMS + 1)], build):
            return bench.zero_loss_ceiling(trial, steps, 25000, "scenario 16")[0]
    finally:
        stop(gw)


def publications(bench, watched, build):
    """Scenario 2's run (1 x 100 tags, QoS 1, every tag changing, 1.5 x bare Paho offered) on
    `build`'s gateway with its listener on, the streams open on its exchange when `watched`."""
    port = free_port()
    during = EventStreams(port, ["e1"] * STREAMS, build) if watched else None
    return bench.gateway_rate("g16p" + ("w" if watched else ""), 1, 1.0, bench.ceilings16,
                              build=build, prometheus=port, during=during)["rate"]


def paired_row(bench, figure, measure, fmt):
    """Each round: each build without streams, then with them (in the round's build order);
    the ratio watched / unwatched of each round, the median of them."""
    rounds = []
    for r in range(bench.rounds):
        rounds.append(bench.per_build(r, lambda b: (measure(False, b), measure(True, b))))
    own = [x[bench.build] for x in rounds]
    ratios = [w / u if u else 0 for u, w in own]
    ratio = median(ratios)
    unwatched, watched = median([u for u, _ in own]), median([w for _, w in own])
    note = " (rounds: " + ", ".join(f"{x:.2f}" for x in ratios) + ")" if len(ratios) > 1 else ""
    bench.row(f"{WATCHED}{figure}{bench.rounds_label()}", fmt(watched),
              f"{fmt(unwatched)} (the same, no stream open)",
              f"{ratio_text(ratio, lambda x: x >= 0.95)}{note}", ">= 0.95",
              "yes" if ratio >= 0.95 else "no",
              bench.versus(rounds, lambda x: x[1] / x[0] if x[0] else 0,
                           fmt="{:.2f} x unwatched".format))


def render(bench, exchanges, build):
    """page_render.js on `build`'s gateway consuming `exchanges` x 100 tags, one datagram sent
    to each: the median run's {rows_ms, tags_ms, fcp_ms} of three (one quick)."""
    port = free_port()
    name = f"g16r{exchanges}"
    gw, udp_port = bench.launch_gateway(name, consumed_list(exchanges), 0, build=build,
                                        prometheus=port)
    try:
        bench.generate(udp_port, exchanges, 10000, count=exchanges, change=1.0)
        if not bench.metrics_until(name, lambda m: m["accepted"] >= exchanges, reads=30):
            raise RuntimeError(f"{name}: not every exchange's datagram was accepted")
        require_page(port, build)
        # e1: on the first page of the list, sorted by name, as a user finds it.
        got = run_json(["node", RENDER, CHROMIUM, f"http://{HOST}:{port}/", "e1", "100",
                        "1" if bench.quick else "3"], timeout=300)
    finally:
        stop(gw)
    runs = sorted(got["runs"], key=lambda x: x["tags_ms"])
    if any(x["exchanges"] == 0 for x in runs):
        raise RuntimeError(f"{name}: the page showed no exchange")
    return runs[len(runs) // 2]


def require_page(port, build):
    """NotInBuild when `build`'s listener on `port` serves no page at `/` (an earlier build has
    the metrics alone): chromium would wait for rows that never come."""
    conn = http.client.HTTPConnection(HOST, port, timeout=10)
    try:
        conn.request("GET", "/")
        response = conn.getresponse()
        response.read()
    finally:
        conn.close()
    if response.status != 200:
        raise NotInBuild(build, f"no status page: HTTP {response.status} for /")


def render_row(bench):
    rounds = [bench.per_build(0, lambda b: (render(bench, 1000, b), render(bench, 1, b)))]
    large, small = rounds[0][bench.build]
    bench.row("status page, time to first render in headless chromium, 1,000 x 100 tags "
              "(ms from navigation: exchange rows shown / an open exchange's 100 tags shown; "
              f"median of {1 if bench.quick else 3} fresh loads)",
              f"{large['rows_ms']:,.0f} / {large['tags_ms']:,.0f} "
              f"(first paint {large['fcp_ms'] or 0:,.0f})",
              f"{small['rows_ms']:,.0f} / {small['tags_ms']:,.0f} (the same page, 1 x 100 tags)",
              f"{large['tags_ms'] / small['tags_ms']:.2f}" if small["tags_ms"] else "-",
              "<= 1,000 ms", "yes" if large["tags_ms"] <= 1000 else "no",
              bench.versus(rounds, lambda x: x[0]["tags_ms"]))


def run(bench):
    print("[16] the status page: the data path watched by 10 browsers, and the page's render",
          flush=True)
    bench.ceilings16 = bench.ceilings.get(1) or bench.paho_ceiling(1)
    duration = 1 if bench.quick else 2
    steps = 1 if bench.quick else 3
    paired_row(bench, "datagrams/s accepted, zero loss, 16 exchanges of 100 tags",
               lambda watched, b: ceiling(bench, duration, steps, watched, b), "{:,.0f}".format)
    paired_row(bench, "tag publications/s, QoS 1, 100 % changing, 1 x 100 tags, tuned broker",
               lambda watched, b: publications(bench, watched, b),
               "{:,.0f}".format)
    render_row(bench)
