"""Scenario 7: the period of produced exchanges at 10 ms, against the load generator sending
the same exchanges on the same schedule."""

import socket

from benchlib.util import HOST, free_port, last_json, stop


def capture(bench, duration):
    """A udp_sink measuring periods (10 ms, the first second skipped): (process, port)."""
    port = free_port(socket.SOCK_DGRAM)
    sink = bench.start_sink(port, "--period-ms", 10, "--skip-ms", 1000, "--duration",
                            duration + 1)
    return sink, port


def gateway_periods(bench, count, duration, build):
    """`build`'s gateway producing `count` exchanges at 10 ms: its sink's JSON."""
    sink, port = capture(bench, duration)
    name = f"g7n{count}"
    config = bench.write_config(
        name, produced=[(5000 + i, 10, 10, f"{HOST}:{port}") for i in range(count)],
        udp_port=free_port(socket.SOCK_DGRAM), build=build)
    try:
        gw = bench.start_gateway(name, config, build=build)
    except Exception:
        stop(sink)
        raise
    got = last_json(sink.communicate(timeout=duration + 30)[0])
    stop(gw)
    return got


def one_round(bench, r, count, duration):
    """The load generator, then each build's gateway (in round r's order), producing `count`
    exchanges: (their sinks' JSON by build, the generator's sink's)."""
    sink, port = capture(bench, duration)
    bench.generate(port, count, count * 100, duration=duration + 1.5, change=0,
                   stamp=False, tags=10, first=5000)
    base = last_json(sink.communicate(timeout=duration + 30)[0])
    runs = bench.per_build(r, lambda build: gateway_periods(bench, count, duration, build))
    print(f"    {count} exchanges: gateway {runs[bench.build]}; generator {base}", flush=True)
    return runs, base


def period_rows(bench, count, jitter_target, measured):
    rounds = [(runs[bench.build], base) for runs, base in measured]
    runs = [runs for runs, _ in measured]
    # The round of median gateway jitter (the absolute target is on it), with its pair.
    got, base = sorted(rounds, key=lambda r: r[0]["p99_jitter_us"])[len(rounds) // 2]
    worst_error = max(r[0]["mean_error_pct"] for r in rounds)
    err_ok = worst_error < 0.1 and all(r[0]["exchanges"] == count for r in rounds)
    bench.row(f"produced period, {count} x 10 ms: mean error (%){bench.rounds_label('worst')}",
              f"{worst_error:.3f} (worst exchange "
              f"{max(r[0]['worst_exchange_error_pct'] for r in rounds):.3f}, "
              f"{min(r[0]['exchanges'] for r in rounds)} seen)",
              f"{max(r[1]['mean_error_pct'] for r in rounds):.3f} (load_generator)", "-",
              "< 0.1 %", "yes" if err_ok else "no",
              bench.versus(runs, lambda got: got["mean_error_pct"],
                           shown=lambda old: f"{max(g['mean_error_pct'] for g in old):.3f}"))
    ratio = got["p99_jitter_us"] / base["p99_jitter_us"] if base["p99_jitter_us"] else 0
    bench.row(f"produced period, {count} x 10 ms: p99 jitter (us){bench.rounds_label()}",
              f"{got['p99_jitter_us']:,.0f} (max {got['max_jitter_us']:,.0f}"
              f"{bench.values_note([r[0]['p99_jitter_us'] for r in rounds])})",
              f"{base['p99_jitter_us']:,.0f} (load_generator)", f"{ratio:.2f}",
              f"<= {jitter_target:,} us",
              "yes" if got["p99_jitter_us"] <= jitter_target else "no",
              bench.versus(runs, lambda got: got["p99_jitter_us"]))


def run(bench):
    print("[7] produced period accuracy at 10 ms", flush=True)
    duration = 2 if bench.quick else 6
    for count, jitter_target in ((100, 200), (1000, 1000)):
        measured = [one_round(bench, r, count, duration) for r in range(bench.rounds)]
        period_rows(bench, count, jitter_target, measured)
