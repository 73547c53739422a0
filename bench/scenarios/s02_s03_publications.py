"""Scenarios 2 and 3: tag publications/s against bare Paho, every tag changing (2) and 10 %
changing (3), in both exchange shapes, at QoS 0 and 1, on both brokers. Each run's CPU per
publication (benchlib.cpu) goes to the report's second table."""

from benchlib.util import (SETUPS, SHAPES, median, median_round, offered_datagrams,
                           ratio_text)


def run(bench):
    print("[2,3] tag publications/s vs bare Paho", flush=True)
    bench.ceilings = {}
    for qos in (0, 1):
        for exchanges, tags in SHAPES:
            for setup, broker in SETUPS:
                bench.use_broker(setup)
                publications_rows(bench, qos, exchanges, tags, setup, broker)
    bench.use_broker("tuned")


def one_round(bench, r, qos, exchanges, tags, results):
    """Bare Paho, then each build's gateway (in round r's order) for each share of tags
    changing, then bare Paho beside the gateway's input; with many small exchanges, each
    build as two gateways too. Appends to results[(change, gateways)] one
    ({build: (ratio, rate, cpu)}, paho, paho with input, paho's cpu)."""
    paho, paho_cpu = bench.paho_run(qos, topics=exchanges * tags, sample=True)
    for change in (1.0, 0.1):
        def one(build):
            got = bench.gateway_rate(f"g2q{qos}c{int(change * 100)}", qos, change, paho,
                                     exchanges=exchanges, tags=tags, build=build, sample=True)
            return got["rate"] / paho if paho else 0, got["rate"], got["cpu"]

        def split(build):
            got = bench.split_gateways_rate(qos, change, paho, exchanges, tags, build=build,
                                            sample=True)
            return got["rate"] / paho if paho else 0, got["rate"], got["cpu"]

        single = bench.per_build(r, one)
        # Not the target's baseline: what bare Paho keeps of its rate when the datagrams the
        # gateway was offered are sent and received beside it.
        loaded = bench.paho_with_input(qos, exchanges * tags, exchanges, tags, change,
                                       offered_datagrams(paho, change, tags))
        results[(change, 1)].append((single, paho, loaded, paho_cpu))
        if exchanges > 1:
            results[(change, 2)].append((bench.per_build(r, split), paho, loaded, paho_cpu))


def measure_rounds(bench, qos, exchanges, tags):
    """Paired rounds: bare Paho, then the gateway, again and again, so that a burst of the
    host's other work (which moved single figures by 20-50 % on this VM) hits a baseline and
    its pair alike. Many small exchanges are also split over two gateway processes: the tuning
    row."""
    results = {(change, parts): [] for change in (1.0, 0.1) for parts in (1, 2)
               if parts == 1 or exchanges > 1}
    for r in range(bench.rounds):
        one_round(bench, r, qos, exchanges, tags, results)
    return results


def rounds_of(rounds, build):
    """One build's rounds as (ratio, rate, paho, paho with input)."""
    return [(runs[build][0], runs[build][1], paho, loaded) for runs, paho, loaded, _ in rounds]


def against_cells(bench, rounds):
    def shown(old):
        ratio, rate, _ = median_round(old)
        return f"{rate:,.0f} ({ratio:.2f} x bare Paho)"

    return bench.versus([runs for runs, _, _, _ in rounds], lambda run: run[1], shown=shown)


def cpu_rows(bench, figure, rounds):
    for build in bench.builds:
        bench.cpu_row(figure, build.label,
                      [runs[build][2] for runs, _, _, _ in rounds if runs.get(build)])
    bench.cpu_row(figure, "bare Paho", [cpu for _, _, _, cpu in rounds])


def publications_rows(bench, qos, exchanges, tags, setup, broker):
    shape = f"{exchanges} x {tags} tags"
    print(f"  QoS {qos}, {shape}, {broker}", flush=True)
    results = measure_rounds(bench, qos, exchanges, tags)
    for (change, parts), rounds in results.items():
        own = rounds_of(rounds, bench.build)
        ratio, rate, paho, loaded = median_round(own)
        label = f"{int(change * 100)} % changing"
        instances = f" as two gateways of {exchanges // 2} exchanges" if parts == 2 else ""
        figure = (f"tag publications/s, QoS {qos}, {label}, {shape}{instances}, {broker}"
                  f"{bench.rounds_label()}")
        bench.row(figure, f"{rate:,.0f}",
                  f"{paho:,.0f} (bare Paho; {loaded:,.0f} with the gateway's datagram input "
                  f"beside it, {loaded / paho if paho else 0:.2f} x)",
                  f"{ratio_text(ratio, lambda r: r >= 0.9)}{bench.ratios_note(own)}", ">= 0.90",
                  "yes" if ratio >= 0.9 else "no", against_cells(bench, rounds))
        cpu_rows(bench, figure, rounds)
        if change == 1.0 and parts == 1:
            # Each build's own per-tag rate, the load scenario 14 multiplies.
            for build in bench.builds:
                rates = [runs[build][1] for runs, _, _, _ in rounds if runs.get(build)]
                if rates:
                    bench.ceilings[("gw", build.label, qos, (exchanges, tags), setup)] = \
                        median(rates)
        if (exchanges, tags) == SHAPES[0] and change == 1.0 and parts == 1:
            bench.paho_rates[(qos, broker)] = paho
            if setup == "tuned":
                bench.ceilings[qos] = paho
                bench.ceilings[("gw", qos)] = rate
