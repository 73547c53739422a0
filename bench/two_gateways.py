#!/usr/bin/env python3
"""One gateway against two gateway processes that share its exchanges, each with its own Paho
and its own connection: the tuning of issue #17 that a user can set (two instances, each with
half of the exchanges). Not a scenario of run.py; it reuses its Bench (brokers, configurations,
counter) on the build that EIP2MQTT_BENCH_BUILD names.

    EIP2MQTT_BENCH_BUILD=build python3 bench/two_gateways.py QOS CHANGE SETUP ROUNDS
    e.g. ... 1 1.0 default 3    (QoS 1, every tag changing, Debian's default broker)

100 exchanges x 10 tags. Each round: bare Paho's rate on the 1,000 topics, then one gateway
with every exchange (as run.py's per-tag rows), then two gateways with 50 exchanges each, each
fed by a load generator of its own at half the datagrams offered to the one. Prints each
round's ratios to bare Paho and their medians. Only 127.0.0.1; every wait is bounded."""
import os
import socket
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import run  # noqa: E402

EXCHANGES, TAGS = 100, 10


def two_gateways_rate(bench, qos, change, ceiling):
    half = EXCHANGES // 2
    gateways, ports = [], []
    for i, name in enumerate(("twoa", "twob")):
        port = run.free_port(socket.SOCK_DGRAM)
        first = 1 + i * half
        config = bench.write_config(name, consumed=[(e, TAGS) for e in range(first, first + half)],
                                    qos=qos, udp_port=port)
        gateways.append((name, bench.start_gateway(name, config)))
        ports.append(port)
    for name, _ in gateways:
        bench.wait_online(name)
    counter = bench.start_counter("b/+/+", qos)
    rate = run.offered_datagrams(ceiling, change, TAGS) // 2
    generators = [bench.start_generator(port, half, rate, bench.d, change=change, tags=TAGS,
                                        first=1 + i * half)
                  for i, port in enumerate(ports)]
    for generator in generators:
        generator.communicate(timeout=bench.d + 60)
    got = bench.finish(counter)
    for _, gateway in gateways:
        run.stop(gateway)
    return got["rate"]


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    qos, change, setup, rounds = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3], int(sys.argv[4])
    bench = run.Bench(False, set())
    one, two = [], []
    try:
        bench.start_broker()
        bench.use_broker(setup)
        for r in range(rounds):
            paho = bench.paho_ceiling(qos, topics=EXCHANGES * TAGS)
            got = bench.gateway_rate("one", qos, change, paho, exchanges=EXCHANGES, tags=TAGS)
            one.append(got["rate"] / paho)
            two.append(two_gateways_rate(bench, qos, change, paho) / paho)
            print(f"round {r + 1}: bare Paho {paho:,.0f}/s; one gateway {one[-1]:.2f} x, "
                  f"two {two[-1]:.2f} x", flush=True)
    finally:
        bench.close()
    print(f"median x bare Paho: one gateway {statistics.median(one):.2f}, two gateways "
          f"{statistics.median(two):.2f}")


if __name__ == "__main__":
    main()
