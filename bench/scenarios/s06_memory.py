"""Scenario 6: resident memory and start-up to READY with 1,000 x 100 consumed and 100
produced exchanges, every tag inline in the YAML and with point lists."""

import os
import socket
import time

from benchlib.util import (HOST, consumed_list, free_port, median, rss_kb, rss_split_kb,
                           run_json, stop, tool)


def run(bench):
    print("[6] memory and start-up: 1,000 x 100 tags consumed + 100 produced", flush=True)
    sink_port = free_port(socket.SOCK_DGRAM)  # nobody listens: produced datagrams vanish
    udp_port = free_port(socket.SOCK_DGRAM)
    runs = 1 if bench.quick else 3
    # The quick form publishes at QoS 0, at twice the rate or more: the 100,000 first values
    # are out sooner.
    qos = 0 if bench.quick else 1
    # The same exchanges written two ways: every tag inline in the YAML (5.4 MB), and the
    # consumed tags as rows of one SCADA point list named by each exchange's `points:`.
    # The third form has the status page on (metrics.listen): what its sparklines keep (25,000
    # tags at most) is counted with the rest.
    page_port = free_port(socket.SOCK_STREAM)
    for form, name, point_list, prometheus in (
            ("inline YAML", "g6", False, 0), ("point lists", "g6p", True, 0),
            ("point lists, status page on", "g6s", True, page_port)):
        def config(build):
            return bench.write_config(
                name, consumed=consumed_list(1000),
                produced=[(5000 + i, 10, 100, f"{HOST}:{sink_port}") for i in range(100)],
                qos=qos, udp_port=udp_port, point_list=point_list, prometheus=prometheus,
                build=build)

        measured = bench.per_build(0, lambda build: startup_and_memory(
            bench, name, config(build), udp_port, runs, build))
        # Same-run floor: yaml-cpp alone parsing the same YAML file with a no-op handler.
        floor = run_json([tool("yaml_parse"), "--file", config(bench.build), "--repeat",
                          str(runs)], timeout=300)
        # The page on: its sparklines (60 floats for each of 25,000 tags at most: 6 MB) and the
        # listener (its threads, a snapshot of the metrics: 1 MB) beside the 32 MB without it.
        rows(bench, form, runs, floor, measured, 39 if prometheus else 32)


def rows(bench, form, runs, floor, measured, limit_mb):
    times, rss_idle, rss_data, hwm, _ = measured[bench.build]
    startup = median(times)
    print(f"    {form}: READY after {', '.join(f'{t:.0f}' for t in times)} ms "
          f"(yaml-cpp alone {floor['median_ms']:.0f} ms on {floor['bytes']:,} bytes); "
          f"RSS idle {rss_idle / 1024:.1f} MB, with data {rss_data / 1024:.1f} MB, peak "
          f"{hwm / 1024:.1f} MB", flush=True)
    # Where the resident memory is, for each build: a difference in code shows apart from one
    # in data.
    for build, m in measured.items():
        if m and m[4]:
            bench.notes.append(f"memory with data, {form}, {build.label}, resident MB by what "
                               "holds it: " +
                               ", ".join(f"{k} {v / 1024:.2f}" for k, v in m[4].items()))
    bench.row(f"resident memory, 1,000 x 100 consumed + 100 produced, all tags published, "
              f"{form} (MB)",
              f"{rss_data / 1024:.1f} (idle {rss_idle / 1024:.1f}, peak {hwm / 1024:.1f})",
              "-", "-", f"<= {limit_mb} MB", "yes" if 0 < rss_data <= limit_mb * 1024 else "no",
              bench.versus([measured], lambda m: m[2] / 1024, fmt="{:.1f}".format))
    bench.row(f"start-up to READY, same configuration, {form} (ms, median of {runs})",
              f"{startup:,.0f}",
              f"{floor['median_ms']:,.0f} (yaml-cpp parsing the same "
              f"{floor['bytes'] / 1e6:.2g} MB YAML, no-op handler)",
              f"{startup / floor['median_ms']:.2f}" if floor["median_ms"] > 0 else "-",
              "<= 200 ms", "yes" if startup <= 200 else "no",
              bench.versus([measured], lambda m: median(m[0])))


def time_to_ready(bench, name, config, path, build):
    """Starts `build`'s gateway with a notify socket at `path`: (process, seconds to
    READY=1)."""
    build.require(config)  # before the clock starts: an earlier build checks it first
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
    listener.bind(path)
    listener.settimeout(0.5)
    start = time.monotonic()
    gw = bench.start_gateway(name, config, notify_socket=path, build=build)
    ready = None
    deadline = start + 30
    while ready is None and time.monotonic() < deadline and gw.poll() is None:
        try:
            if b"READY=1" in listener.recv(4096):
                ready = time.monotonic() - start
        except socket.timeout:
            pass
    listener.close()
    if ready is None:
        build.start_failed(gw, os.path.join(bench.tmp, name + ".log"))
        stop(gw)
        raise RuntimeError(f"gateway {name} did not send READY=1")
    return gw, ready


def memory(bench, name, gw, udp_port, build):
    """VmRSS 1 s after coming online, VmRSS once one datagram per consumed exchange was
    published, VmHWM (all kB), and the resident kB then by what holds it (rss_split_kb)."""
    bench.wait_online(name, proc=gw, build=build)
    time.sleep(1)
    rss_idle = rss_kb(gw.pid)
    # One datagram per consumed exchange: every image filled, every tag published.
    bench.generate(udp_port, 1000, 10000, count=1000, change=1.0)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        m = bench.metrics(name)
        if m and m["accepted"] >= 1000 and m["buffered"] == 0:
            break
    return rss_idle, rss_kb(gw.pid), rss_kb(gw.pid, "VmHWM"), rss_split_kb(gw.pid)


def startup_and_memory(bench, name, config, udp_port, runs, build):
    """Start-up times (ms) to READY=1 over `runs` starts of `run -c config`, and the memory of
    the last one (`memory`)."""
    times = []
    rss_idle = rss_data = hwm = 0
    split = {}
    for n in range(runs):
        notify = os.path.join(bench.tmp, f"notify-{name}-{n}-{build.new}.sock")
        gw, ready = time_to_ready(bench, name, config, notify, build)
        times.append(ready * 1000)
        if n == runs - 1:
            rss_idle, rss_data, hwm, split = memory(bench, name, gw, udp_port, build)
        stop(gw)
    times.sort()
    return times, rss_idle, rss_data, hwm, split
