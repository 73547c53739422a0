"""Scenario 14: publications/s under overload. Each build is offered 5 x its own per-tag rate
(scenario 2's, by QoS, shape and broker), every tag changing, in both exchange shapes, at QoS
0 and 1, on both brokers; then the reference load (100 exchanges of 1 lint + 10 dints, 6,000
datagrams/s, QoS 1, Debian's default broker), with the Node-RED flow peer fed the same in the
same rounds. Rates at the subscriber over its first-to-last span; CPU per publication, the
gateway's thread by thread, to the report's second table."""

from benchlib import node_red
from benchlib.util import BROKERS, SETUPS, SHAPES, median, ratio_text

OVERLOAD = 5  # x the build's own sustained per-tag rate
# The reference load: 100 exchanges x (ts lint + 10 dints), 6,000 datagrams/s.
REFERENCE_SHAPE, REFERENCE_DATAGRAMS, REFERENCE_SETUP = (100, 11), 6000, "default"
PEER_ROW = "Node-RED flow peer (udp in -> function -> mqtt out, MQTT 3.1.1)"


def gateway_run(bench, build, qos, shape, datagrams):
    exchanges, tags = shape
    got = bench.gateway_rate(f"g14q{qos}", qos, 1.0, 0, exchanges=exchanges, tags=tags,
                             build=build, sample=True, datagrams=datagrams, threads=True)
    return {"rate": got["rate"], "cpu": got["cpu"], "offered": datagrams}


def overload_run(bench, build, qos, shape, setup):
    of_scenario_2 = ("gw", build.label, qos, shape, setup) in bench.ceilings
    ceiling = bench.gateway_ceiling(build, qos, shape, setup)
    out = gateway_run(bench, build, qos, shape, max(100, round(OVERLOAD * ceiling / shape[1])))
    out["ceiling"] = ceiling
    out["source"] = "of scenario 2" if of_scenario_2 else "in a short run before"
    return out


def peer_run(bench, peer, qos, shape, datagrams):
    """The Node-RED flow offered `datagrams`/s of `shape`, counted as a gateway is."""
    exchanges, tags = shape
    counter = bench.start_counter(f"{peer.base}/+/+", qos)
    gen, sampler = bench.run_load(
        bench.generator_args(peer.udp_port, exchanges, datagrams, duration=bench.d, change=1.0,
                             tags=tags),
        bench.d + 60, "load generator", {"peer": [peer.pid], "subscriber": [counter.pid]},
        True, ("peer",))
    got = bench.finish(counter, timeout=bench.d + 300)
    print(f"    Node-RED: offered {gen['rate']:.0f} datagrams/s x {tags} tags; received "
          f"{got['messages']} msgs at {got['rate']:.0f}/s", flush=True)
    return {"rate": got["rate"], "cpu": sampler.per_publication(got["rate"], bench.d),
            "offered": datagrams}


def gateway_cpu(run):
    return (run["cpu"] or {}).get("gateway", 0)


def met_cell(bench, rounds):
    """Whether this build's rate is >= 1.0 x the earlier build's and its gateway CPU per
    publication <= it: from the medians of the rounds' ratios; "-" without --against."""
    if bench.against is None:
        return "-"
    pairs = [(r[bench.build], r.get(bench.against)) for r in rounds]
    if any(old is None for _, old in pairs):
        return "-"
    rate = [new["rate"] / old["rate"] for new, old in pairs if old["rate"]]
    cpu = [gateway_cpu(new) / gateway_cpu(old) for new, old in pairs if gateway_cpu(old)]
    text = "yes" if rate and median(rate) >= 1.0 else "no"
    if cpu:
        return text + (f"; CPU/publication {median(cpu):.2f} x: "
                       f"{'yes' if median(cpu) <= 1.0 else 'no'}")
    return text + "; CPU/publication not sampled"


def targets(bench):
    label = bench.against.label if bench.against else "REV"
    return f">= 1.0 x {label} (and gateway CPU/publication <= {label}'s)"


def cpu_rows(bench, figure, rounds, peer=None):
    for build in bench.builds:
        bench.cpu_row(figure, build.label, [r[build]["cpu"] for r in rounds if r.get(build)])
    if peer:
        bench.cpu_row(figure, "Node-RED", [p["cpu"] for p in peer])


def overload_row(bench, qos, shape, setup, broker):
    exchanges, tags = shape
    print(f"  QoS {qos}, {exchanges} x {tags} tags, {broker}", flush=True)
    bench.use_broker(setup)
    rounds = [bench.per_build(r, lambda b: overload_run(bench, b, qos, shape, setup))
              for r in range(bench.rounds)]
    own = [r[bench.build] for r in rounds]
    rate = median([o["rate"] for o in own])
    offered, ceiling = own[0]["offered"], own[0]["ceiling"]
    figure = (f"overload tag publications/s, QoS {qos}, 100 % changing, {exchanges} x {tags} "
              f"tags, offered {OVERLOAD} x own rate, {broker}{bench.rounds_label()}")
    bench.row(figure, f"{rate:,.0f}{bench.values_note([o['rate'] for o in own])}",
              f"offered {offered:,} datagrams/s = {offered * tags:,} tag changes/s "
              f"({OVERLOAD} x its {ceiling:,.0f}/s {own[0]['source']})", "-", targets(bench),
              met_cell(bench, rounds),
              bench.versus(rounds, lambda o: o["rate"],
                           shown=lambda old: f"{median([o['rate'] for o in old]):,.0f} "
                                             f"(offered {OVERLOAD} x {old[0]['ceiling']:,.0f}/s)"))
    cpu_rows(bench, figure, rounds)


def reference_rows(bench):
    """The reference load on each build and on the Node-RED flow, in the same rounds (the peer
    first in odd rounds, last in even ones)."""
    exchanges, tags = REFERENCE_SHAPE
    # Debian's default broker, unless EIP2MQTT_BENCH_SETUPS leaves it out.
    setup = REFERENCE_SETUP if REFERENCE_SETUP in dict(SETUPS) else SETUPS[0][0]
    broker = dict(BROKERS)[setup]
    print(f"  the reference load: {exchanges} x {tags} tags, {REFERENCE_DATAGRAMS:,} datagrams/s, "
          f"QoS 1, {broker}, with the Node-RED flow", flush=True)
    bench.use_broker(setup)
    peer = node_red.NodeRed(bench.broker_port, 1, log_dir=bench.tmp).start()
    bench.procs.append(peer.proc)
    rounds, peer_rounds = [], []
    try:
        for r in range(bench.rounds):
            if r % 2:
                peer_rounds.append(peer_run(bench, peer, 1, REFERENCE_SHAPE, REFERENCE_DATAGRAMS))
            rounds.append(bench.per_build(r, lambda b: gateway_run(bench, b, 1, REFERENCE_SHAPE,
                                                                   REFERENCE_DATAGRAMS)))
            if not r % 2:
                peer_rounds.append(peer_run(bench, peer, 1, REFERENCE_SHAPE, REFERENCE_DATAGRAMS))
    finally:
        peer.stop()
    shape = f"{exchanges} x {tags} tags (ts lint + 10 dints), {REFERENCE_DATAGRAMS:,} datagrams/s"
    own = [r[bench.build] for r in rounds]
    rate = median([o["rate"] for o in own])
    peer_rates = [p["rate"] for p in peer_rounds]
    figure = (f"overload tag publications/s, QoS 1, 100 % changing, {shape} (the reference load), "
              f"{broker}{bench.rounds_label()}")
    bench.row(figure, f"{rate:,.0f}{bench.values_note([o['rate'] for o in own])}",
              f"offered {REFERENCE_DATAGRAMS * tags:,} tag changes/s; the Node-RED flow: "
              f"{median(peer_rates):,.0f} (next row)", "-", targets(bench),
              met_cell(bench, rounds), bench.versus(rounds, lambda o: o["rate"]))
    cpu_rows(bench, figure, rounds)
    peer_row(bench, rounds, peer_rounds, shape, broker)


def peer_row(bench, rounds, peer_rounds, shape, broker):
    ratios = [r[bench.build]["rate"] / p["rate"] if p["rate"] else 0
              for r, p in zip(rounds, peer_rounds)]
    ratio = median(ratios)
    own = [r[bench.build]["rate"] for r in rounds]
    peer_rates = [p["rate"] for p in peer_rounds]
    figure = (f"{PEER_ROW}: tag publications/s, QoS 1, {shape}, {broker}"
              f"{bench.rounds_label()}")
    note = "; rounds: " + ", ".join(f"{x:.2f}" for x in ratios) if len(ratios) > 1 else ""

    def shown(old):
        olds = [o["rate"] for o in old]
        versus_peer = median([o / p["rate"] for o, p in zip(olds, peer_rounds) if p["rate"]]
                             or [0])
        return f"{median(olds):,.0f} ({versus_peer:.2f} x Node-RED)"

    bench.row(figure, f"{median(own):,.0f}",
              f"{median(peer_rates):,.0f} (Node-RED {node_red.version()}, one flow, one "
              f"connection{bench.values_note(peer_rates)})",
              f"{ratio_text(ratio, lambda x: x >= 1.0)}{note}", ">= 1.0 x Node-RED",
              "yes" if ratio >= 1.0 else "no",
              bench.versus(rounds, lambda o: o["rate"], shown=shown))
    cpu_rows(bench, figure, rounds, peer_rounds)


def run(bench):
    print(f"[14] overload: {OVERLOAD} x each build's own per-tag rate; the reference load beside "
          "the Node-RED flow", flush=True)
    node_red.require_installed()
    for qos in (0, 1):
        for shape in SHAPES:
            for setup, broker in SETUPS:
                overload_row(bench, qos, shape, setup, broker)
    reference_rows(bench)
    bench.use_broker("tuned")
