"""Scenario 5: latency from a datagram's send to the subscriber, against bare Paho publishing
stamped messages at the same message rate."""

from benchlib.util import (HOST, PAHO_WINDOW, SETUPS, consumed_list, median, median_round,
                           ratio_text, run_json, stop, tool)

# The first half second of each run, baseline and gateway alike, is not measured: there every
# process comes out of idle, and that start (not the rate) made most of the p99.
SKIP_MS = "500"


def run(bench):
    print("[5] latency datagram -> subscriber", flush=True)
    duration = 0.8 if bench.quick else 10
    # (exchanges, tags, datagrams/s, changing): 10 x 10 at 10k datagrams/s with one tag
    # (`ts`) changing, and 100 x 10 at 2k datagrams/s with `ts` and one more tag changing.
    shapes = ((10, 10, 10000, 0.1), (100, 10, 2000, 0.2))
    for qos in (0, 1):
        for shape in shapes:
            for setup, broker in SETUPS:
                bench.use_broker(setup)
                latency_row(bench, qos, shape, duration, setup, broker)
    bench.use_broker("tuned")


def paho_latency(bench, qos, topics, messages, duration):
    """The baseline: bare Paho publishing stamped messages at the same message rate."""
    counter = bench.start_counter("p/+/+", qos, extra=["--stamp-all", "--skip-ms", SKIP_MS])
    run_json([tool("paho_publisher"), "--url", f"tcp://{HOST}:{bench.broker_port}",
              "--window", str(PAHO_WINDOW), "--qos", str(qos), "--rate", str(messages),
              "--stamp", "--duration", str(duration), "--topics", str(topics)],
             timeout=duration + 60)
    return bench.finish(counter)


def gateway_latency(bench, qos, shape, duration, build):
    exchanges, tags, datagrams, change = shape
    name = f"g5q{qos}"
    gw, udp_port = bench.launch_gateway(name, consumed_list(exchanges, tags), qos, build=build)
    # Warm-up: one datagram per exchange, so that every tag's first value (a one-off burst of
    # exchanges x tags retained messages, not a rate) is published before the measured run;
    # the counter skips the retained values it is then sent.
    bench.generate(udp_port, exchanges, 1000, count=exchanges, change=change, tags=tags)
    if bench.quick:  # every warm-up datagram accepted and its tags published: no settling
        bench.metrics_until(name, lambda m: m["accepted"] >= exchanges and
                            m.get("buffered", 0) == 0)
    else:
        bench.settled_metrics(name)
    counter = bench.start_counter("b/+/+", qos, extra=["--skip-ms", SKIP_MS])
    bench.generate(udp_port, exchanges, datagrams, duration=duration, change=change,
                   tags=tags, extra=["--request-id", "1"])
    got = bench.finish(counter)
    stop(gw)
    return got


def measure_rounds(bench, qos, shape, duration):
    """Paired rounds: bare Paho, then each build's gateway (in the round's order). Per round,
    {build: (p99 ratio to bare Paho, gateway's counter JSON, bare Paho's)}."""
    exchanges, tags, datagrams, change = shape
    per_datagram = round(change * tags)
    rounds = []
    for r in range(bench.rounds):
        paho = paho_latency(bench, qos, exchanges * per_datagram, datagrams * per_datagram,
                            duration)

        def one(build):
            got = gateway_latency(bench, qos, shape, duration, build)
            print(f"    qos{qos} {build.label}: gateway n={got['latency_n']} p50 "
                  f"{got['p50_us']} p99 {got['p99_us']} max {got['max_us']}; paho "
                  f"n={paho['latency_n']} p50 {paho['p50_us']} p99 {paho['p99_us']} max "
                  f"{paho['max_us']}", flush=True)
            return got["p99_us"] / paho["p99_us"] if paho["p99_us"] else 0, got, paho

        rounds.append(bench.per_build(r, one))
    return rounds


def latency_row(bench, qos, shape, duration, setup, broker):
    exchanges, tags, datagrams, change = shape
    messages = datagrams * round(change * tags)
    print(f"  QoS {qos}, {exchanges} x {tags} tags, {messages} msgs/s, {broker}", flush=True)
    runs = measure_rounds(bench, qos, shape, duration)
    rounds = [r[bench.build] for r in runs]
    # The round of median ratio, each gateway run with the baseline measured just before it;
    # the gateway's p99 of every round is listed.
    ratio, got, paho = median_round(rounds)
    p99 = median([r[1]["p99_us"] for r in rounds])
    absolute = setup == "tuned"  # the 1 ms target is the tuned broker's
    ok = ratio <= 1.5 and (p99 <= 1000 or not absolute)

    def shown(old):
        old_ratio, old_got, _ = median_round(old)
        return f"{old_got['p99_us']:,.0f} ({old_ratio:.2f} x bare Paho)"

    bench.row(f"latency datagram -> subscriber p99, QoS {qos}, {exchanges} x {tags} tags, "
              f"{messages:,} msgs/s, {broker} (us){bench.rounds_label()}",
              f"{got['p99_us']:,.0f} (p50 {got['p50_us']:,.0f}, max {got['max_us']:,.0f}"
              f"{bench.values_note([r[1]['p99_us'] for r in rounds])})",
              f"{paho['p99_us']:,.0f} (bare Paho p50 {paho['p50_us']:,.0f}, "
              f"max {paho['max_us']:,.0f})",
              f"{ratio_text(ratio, lambda r: r <= 1.5)}{bench.ratios_note(rounds)}",
              "<= 1,000 us and <= 1.5" if absolute else "<= 1.5", "yes" if ok else "no",
              bench.versus(runs, lambda run: run[1]["p99_us"], shown=shown))
