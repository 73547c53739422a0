"""Scenario 8: overload, 5 x the gateway's per-tag QoS 1 ceiling for 10 s with 100 x 100 tags:
memory, newest value wins, datagrams read, and the publish queue's bound."""

import json
import os
import subprocess
import time

from benchlib.util import FINAL_VALUE, HOST, TAGS, consumed_list, last_json, rss_kb, stop

NAME = "g8"


def metrics_samples(path):
    samples = []
    with open(path) as f:
        for line in f:
            try:
                samples.append(json.loads(line))
            except ValueError:
                pass
    return samples


def overload(bench, rate, duration, build):
    """Runs the overload on `build`: what rows() reports, as a dict."""
    gw, udp_port = bench.launch_gateway(NAME, consumed_list(100), 1, build=build)
    log_path = os.path.join(bench.tmp, f"{NAME}-metrics.log")
    metrics_log = open(log_path, "w")
    metrics = subprocess.Popen(["mosquitto_sub", "-h", HOST, "-p", str(bench.broker_port),
                                "-W", str(duration + 90), "-t", f"b/_gateway/{NAME}/metrics"],
                               stdout=metrics_log, stderr=subprocess.DEVNULL)
    bench.procs.append(metrics)
    counter = bench.start_counter("b/+/+", 1, extra=["--expect-last", str(FINAL_VALUE),
                                                     "--expect-topics", str(100 * TAGS)],
                                  idle_ms=10000, max_s=duration + 120)
    time.sleep(0.5)
    rss0 = rss_kb(gw.pid)
    gen = bench.start_generator(udp_port, 100, rate, duration, change=1.0,
                                extra=["--final-value", str(FINAL_VALUE)])
    peak = rss0
    deadline = time.monotonic() + duration + 30
    while gen.poll() is None and time.monotonic() < deadline:
        peak = max(peak, rss_kb(gw.pid))
        time.sleep(0.1)
    sent = last_json(gen.communicate(timeout=10)[0])
    sent_at = time.monotonic()
    got = bench.finish(counter, timeout=duration + 150)
    settle_ms = (time.monotonic() - sent_at) * 1000
    peak = max(peak, rss_kb(gw.pid))
    # The count of accepted datagrams once it stopped moving: the last sample of the metrics
    # log can be a second old when the counter is done, before the last datagrams were
    # counted (650 of 10,550 short in one run, while the kernel's RcvbufErrors did not move).
    final = bench.settled_metrics(NAME)
    stop(metrics)
    metrics_log.close()
    stop(gw)
    samples = metrics_samples(log_path)
    last = samples[-1] if samples else {}
    return {"sent": sent, "got": got, "total": sent["sent"] + sent["final"],
            "settle_ms": settle_ms, "rss0": rss0, "peak": peak,
            "max_buffered": max((s.get("buffered", 0) for s in samples), default=-1),
            "last": last, "accepted": (final or last).get("accepted", 0)}


def log(r, ceiling, label):
    sent, got, last = r["sent"], r["got"], r["last"]
    print(f"    {label}: offered {sent['rate']:.0f} datagrams/s x {TAGS} = "
          f"{sent['rate'] * TAGS:.0f} tag updates/s (ceiling {ceiling:.0f}/s); RSS "
          f"{r['rss0'] / 1024:.1f} -> peak {r['peak'] / 1024:.1f} MB; delivered {got['messages']} "
          f"at {got['rate']:.0f}/s; last value ok {got['last_ok']}/{100 * TAGS} bad "
          f"{got['last_bad']}; max buffered {r['max_buffered']}; coalesced "
          f"{last.get('publications_coalesced')}, dropped {last.get('publications_dropped')}",
          flush=True)


def growth_mb(r):
    return (r["peak"] - r["rss0"]) / 1024


def rows(bench, runs):
    r = runs[bench.build]
    got, max_buffered = r["got"], r["max_buffered"]
    topics = 100 * TAGS
    growth = growth_mb(r)
    bench.row("overload 5 x ceiling: RSS growth (MB)", f"{growth:.1f}",
              f"{r['rss0'] / 1024:.1f} MB before", "-", "<= 5 MB", "yes" if growth <= 5 else "no",
              bench.versus([runs], growth_mb, fmt="{:.1f}".format))
    bench.row("overload: newest value of each tag wins (topics ending on the last value)",
              f"{got['last_ok']:,} / {topics:,} (all seen {r['settle_ms']:,.0f} ms after the last "
              "send)", "-", "-", "all",
              "yes" if got["last_ok"] == topics and got["last_bad"] == 0 else "no",
              bench.versus([runs], lambda o: o["got"]["last_ok"],
                           fmt=lambda v: f"{v:,} / {topics:,}"))
    bench.row("overload: datagrams accepted / sent (UDP drops before the gateway reads them)",
              f"{r['accepted']:,} / {r['total']:,}", "-", "-", "all (incl. the final ones)",
              "yes" if r["accepted"] == r["total"] else "no",
              bench.versus([runs], lambda o: o["accepted"] / o["total"],
                           shown=lambda old: f"{old[0]['accepted']:,} / {old[0]['total']:,}"))
    # Latest value per topic: the queue never holds more than one message per topic the
    # gateway publishes (tags, each exchange's _status, its own state and metrics).
    bound = topics + 100 + 2
    bench.row("overload: largest publish queue seen (messages)", f"{max_buffered:,}",
              f"{bound:,} topics ({topics:,} tags, 100 _status, 2 of the gateway)", "-",
              "bounded (<= topics)", "yes" if 0 <= max_buffered <= bound else "no",
              bench.versus([runs], lambda o: o["max_buffered"], fmt="{:,}".format))


def run(bench):
    print("[8] overload: 5 x the publication ceiling for 10 s (100 x 100 tags, QoS 1)",
          flush=True)
    duration = 1.5 if bench.quick else 10
    ceiling = bench.ceilings.get(("gw", 1)) or bench.ceilings.get(1) or bench.paho_ceiling(1)
    rate = max(100, round(5 * ceiling / TAGS))

    def one(build):
        r = overload(bench, rate, duration, build)
        log(r, ceiling, build.label)
        return r

    rows(bench, bench.per_build(0, one))
