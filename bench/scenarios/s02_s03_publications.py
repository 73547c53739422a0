"""Scenarios 2 and 3: tag publications/s against bare Paho, every tag changing (2) and 10 %
changing (3), in both exchange shapes, at QoS 0 and 1, on both brokers."""

from benchlib.util import SETUPS, SHAPES, median_round, offered_datagrams, ratio_text


def run(bench):
    print("[2,3] tag publications/s vs bare Paho", flush=True)
    bench.ceilings = {}
    for qos in (0, 1):
        for exchanges, tags in SHAPES:
            for setup, broker in SETUPS:
                bench.use_broker(setup)
                publications_rows(bench, qos, exchanges, tags, setup, broker)
    bench.use_broker("tuned")


def measure_rounds(bench, qos, exchanges, tags):
    """Paired rounds: bare Paho, then the gateway, again and again, so that a burst of the
    host's other work (which moved single figures by 20-50 % on this VM) hits a baseline and
    its pair alike. Many small exchanges are also split over two gateway processes: the tuning
    row. {(change, gateways): [(ratio, rate, paho, paho with input), ...]}"""
    split = exchanges > 1
    results = {(change, parts): [] for change in (1.0, 0.1) for parts in (1, 2)
               if parts == 1 or split}
    for _ in range(bench.rounds):
        paho = bench.paho_ceiling(qos, topics=exchanges * tags)
        for change in (1.0, 0.1):
            got = bench.gateway_rate(f"g2q{qos}c{int(change * 100)}", qos, change, paho,
                                     exchanges=exchanges, tags=tags)
            # Not the target's baseline: what bare Paho keeps of its rate when the datagrams
            # the gateway was offered are sent and received beside it.
            loaded = bench.paho_with_input(qos, exchanges * tags, exchanges, tags, change,
                                           offered_datagrams(paho, change, tags))
            results[(change, 1)].append((got["rate"] / paho if paho else 0, got["rate"],
                                         paho, loaded))
            if split:
                got = bench.split_gateways_rate(qos, change, paho, exchanges, tags)
                results[(change, 2)].append((got["rate"] / paho if paho else 0,
                                             got["rate"], paho, loaded))
    return results


def publications_rows(bench, qos, exchanges, tags, setup, broker):
    shape = f"{exchanges} x {tags} tags"
    print(f"  QoS {qos}, {shape}, {broker}", flush=True)
    results = measure_rounds(bench, qos, exchanges, tags)
    for (change, parts), rounds in results.items():
        ratio, rate, paho, loaded = median_round(rounds)
        label = f"{int(change * 100)} % changing"
        instances = f" as two gateways of {exchanges // 2} exchanges" if parts == 2 else ""
        bench.row(f"tag publications/s, QoS {qos}, {label}, {shape}{instances}, {broker}"
                  f"{bench.rounds_label()}",
                  f"{rate:,.0f}",
                  f"{paho:,.0f} (bare Paho; {loaded:,.0f} with the gateway's datagram input "
                  f"beside it, {loaded / paho if paho else 0:.2f} x)",
                  f"{ratio_text(ratio, lambda r: r >= 0.9)}"
                  f"{bench.ratios_note(rounds)}", ">= 0.90",
                  "yes" if ratio >= 0.9 else "no")
        first_shape = (exchanges, tags) == SHAPES[0]
        if change == 1.0 and parts == 1 and setup == "tuned" and first_shape:
            bench.ceilings[qos] = paho
            bench.ceilings[("gw", qos)] = rate
