"""Scenario 18: a fleet. N gateways (N = 1, 2, 4, 8; 1 and 2 with --quick), each in a network
namespace of its own with its own simulated PLCs, publishing into a three-node ejabberd 23.01
cluster (Debian's; benchlib.ejabberd_cluster) with a subscriber on every node (benchlib.fleet).

The network (benchlib.netns): a hub namespace holds the cluster (epmd, three nodes, MQTT on
1883, 1884 and 1885 of 0.0.0.0 *there*) and a bridge at 10.218.0.1/24; gateway i's namespace
is joined to the bridge by a veth pair (10.218.0.(10 + i)). Its PLCs are the bench's load
generator, run inside that namespace and sending to the gateway's UDP port 18246 on the
namespace's loopback: each gateway has a segment of its own, as at a plant. Its `mqtt.url`
lists the three nodes from node i % 3 on, so that the fleet spreads over the cluster. Nothing
is addressed outside the namespaces made here; all of them are deleted at the end, the nodes
and their epmd stopped, whatever happened.

The offered load, per gateway, is a fixed plant (PLANT): 10 exchanges of 50 tags (`ts`, the
send time, a lint, then 49 dints), each sent every 100 ms (100 datagrams/s), a fifth of the
tags (10, `ts` among them) changing in every datagram: 1,000 tag updates/s per gateway (8,000
for the fleet of 8), published at QoS 1, what a historian that must not miss a sample asks.
(Every tag changing, 5,000 a gateway, is more than one ejabberd session takes at QoS 1 on a
2-core machine: one gateway alone then loses most of its updates to coalescing.) Each gateway
first gets one datagram per exchange with every tag 0: its 500 first values, published and
acknowledged (its metrics say so) before the subscribers subscribe, as in scenario 5, since
that one-off burst is more than its window in flight and would cost the next values. Then a
subscriber per node (bench/mqtt_counter, QoS 1, `b/+/+`) counts every tag update and the
latency of each `ts` (send -> delivery, the first 0.5 s left out, as in scenario 5), over 10 s
of load (3 s with --quick).

Per N, three rows: tag updates/s delivered (the sum over the subscribers, each node's in
parentheses) against those offered (published x 3 subscribers), what was lost (expected -
delivered, per subscriber) and where it went (coalesced by the gateways while they waited for
the broker's acknowledgements, datagrams not accepted, subscriber sessions ejabberd closed);
latency p99 and p50 over every node's samples; CPU per gateway and per broker node (process CPU
time / wall time over the loaded part, % of one core; a node is its beam.smp), with the
machine's idle time. A run is behind when something was lost or the subscribers were still
receiving more than LAG_S after the load ended (a backlog); the busiest node is named then.
Three rows close it: the largest N carried with zero loss, the first N behind, and the most
tag updates/s the cluster delivered in a run (its ceiling, once that run is behind).

Needs root, iproute2 and ejabberd: it runs only when asked (`bench/run.sh --only 18`), never in
a run of every scenario."""

import os
import time

from benchlib import netns
from benchlib.ejabberd_cluster import EjabberdCluster
from benchlib.ejabberd_cluster import unavailable as no_ejabberd
from benchlib.fleet import FleetRun, Plant

COUNTS, QUICK_COUNTS = (1, 2, 4, 8), (1, 2)
PLANT = Plant(exchanges=10, tags=50, period_ms=100, change=0.2, qos=1)
SEGMENT = "10.218.0"  # the bridge's /24, inside the scenario's own namespaces
LAG_S = 1.0


def unavailable():
    """Why the scenario cannot run here ("" when it can)."""
    return netns.unavailable() or no_ejabberd()


def percentile(values, q):
    values = sorted(values)
    return values[min(len(values) - 1, int(q * len(values)))] if values else 0.0


def cores(cpu, role):
    """A process's CPU over the loaded part, in cores, from CpuSampler.per_publication."""
    return cpu[role] * cpu["rate"] / 1e6 if cpu and role in cpu else 0.0


def cpu_table_entry(cpu):
    """The report's CPU table entry (us per publication, by report.CPU_ROLES) from the
    sampler's figures process by process."""
    if not cpu:
        return None
    out = {key: cpu[key] for key in ("rate", "machine", "idle")}
    for role, prefix in (("gateway", "gw"), ("load generator", "gen"), ("broker", "node"),
                         ("subscriber", "sub")):
        out[role] = sum(v for k, v in cpu.items()
                        if k.startswith(prefix) and k[len(prefix):].isdigit())
    return out


def summary(run, raw):
    """What a run's rows say, from FleetRun.measure's figures."""
    cpu, metrics, got = raw["cpu"], raw["metrics"], raw["got"]
    expected = sum(PLANT.expected(s) for s in raw["sent"])
    delivered = [counted["updates"] for counted, _ in got]
    samples = [x for _, dump in got for x in dump]
    accepted = sum(m.get("accepted", 0) for m in metrics.values())
    out = {
        "offered": raw["offered"], "expected": expected, "delivered": delivered,
        "lost": [max(0, expected - d) for d in delivered],
        "duplicates": sum(max(0, d - expected) for d in delivered),
        "rates": [counted["rate"] for counted, _ in got],
        "lag_s": max(counted["lag_s"] for counted, _ in got),
        "p50_ms": percentile(samples, 0.50) / 1000, "p99_ms": percentile(samples, 0.99) / 1000,
        "latency_n": len(samples),
        "gateways": [cores(cpu, f"gw{i}") for i in range(run.count)],
        "nodes": [cores(cpu, f"node{j}") for j in range(len(run.cluster.nodes))],
        "idle": cpu["idle"] if cpu else 0.0, "cpu": cpu_table_entry(cpu),
        "coalesced": sum(m.get("publications_coalesced", 0) for m in metrics.values()),
        # The warm-up's datagrams (one per exchange) were accepted too.
        "not_accepted": (sum(raw["sent"]) + run.count * PLANT.exchanges - accepted
                         if len(metrics) == run.count else None),
        "closed": raw["closed"],
    }
    out["behind"] = max(out["lost"]) > 0 or out["lag_s"] > LAG_S
    # Where the gateways were connected: node i % 3 first, so the fleet spreads over the nodes.
    spread = [sum(m.get("broker", "").endswith(f":{n.port}") for m in metrics.values())
              for n in run.cluster.nodes]
    print(f"    {run.build.label}, {run.count} gateways (per node {spread}): sent "
          f"{sum(raw['sent'])} datagrams, {expected} updates; delivered {delivered} (lag "
          f"{out['lag_s']:.2f} s); p50 {out['p50_ms']:.1f} ms p99 {out['p99_ms']:.1f} ms (n="
          f"{len(samples)}); coalesced {out['coalesced']}, not accepted {out['not_accepted']}, "
          f"subscriber sessions closed {out['closed']}; CPU gateways "
          f"{' '.join(f'{c:.2f}' for c in out['gateways'])}, nodes "
          f"{' '.join(f'{c:.2f}' for c in out['nodes'])} cores, idle {out['idle']:.0f} %",
          flush=True)
    return out


def fleet_run(bench, segment, members, cluster, build, count, duration):
    run = FleetRun(bench, segment, members, cluster, build, count, duration, PLANT)
    try:
        return summary(run, run.measure())
    finally:
        run.close()


def percent(values):
    return " / ".join(f"{100 * v:.0f}" for v in values) + " %"


def lost_text(got):
    where = []
    if got["coalesced"]:
        where.append(f"{got['coalesced']:,} coalesced by the gateways")
    if got["not_accepted"]:
        where.append(f"{got['not_accepted']:,} datagrams not accepted")
    if got["closed"]:
        where.append(f"{got['closed']} subscriber session{'s' if got['closed'] > 1 else ''} "
                     "closed by ejabberd, its queue overloaded")
    if got["duplicates"]:
        where.append(f"{got['duplicates']:,} duplicates")
    return (f"lost {max(got['lost']):,} of {got['expected']:,} per subscriber at worst"
            + (f": {', '.join(where)}" if where else ""))


def busiest(got):
    node = max(range(len(got["nodes"])), key=lambda j: got["nodes"][j])
    return (f"node {node} busiest at {100 * got['nodes'][node]:.0f} % of a core, the cluster "
            f"{100 * sum(got['nodes']):.0f} %")


def gateways_text(count):
    return f"{count} gateway{'s' if count > 1 else ''}"


def fleet_rows(bench, count, runs):
    """The three rows of one N: delivered updates/s (and loss), latency, CPU."""
    got = runs[bench.build]
    shape = (f"{gateways_text(count)}, each {PLANT.exchanges} x {PLANT.tags} tags every "
             f"{PLANT.period_ms} ms ({PLANT.changed} changing), QoS {PLANT.qos}, three-node "
             "ejabberd 23.01 cluster, a subscriber per node")
    offered = 3 * got["offered"]
    ratio = sum(got["rates"]) / offered if offered else 0.0
    per_node = " / ".join(f"{r:,.0f}" for r in got["rates"])
    bench.row(f"fleet: tag updates/s delivered, {shape}",
              f"{sum(got['rates']):,.0f} (per node {per_node}; {lost_text(got)})",
              f"{offered:,.0f} offered ({got['offered']:,.0f}/s published x 3 subscribers)",
              f"{ratio:.2f}", "zero loss", "yes" if max(got["lost"]) == 0 else "no",
              bench.versus([runs], lambda r: sum(r["rates"])))
    bench.row(f"fleet: latency datagram -> subscriber p99 (ms), {gateways_text(count)}, every "
              "node's samples",
              f"{got['p99_ms']:,.1f} (p50 {got['p50_ms']:,.1f}, n {got['latency_n']:,})",
              "-", "-", "-", "-",
              bench.versus([runs], lambda r: r["p99_ms"], fmt="{:,.1f}".format))
    gateways = got["gateways"]
    bench.row(f"fleet: CPU per gateway and per broker node (% of one core), "
              f"{gateways_text(count)}",
              f"{100 * sum(gateways) / len(gateways):.0f} % per gateway (max "
              f"{100 * max(gateways):.0f} %)",
              f"nodes {percent(got['nodes'])} (machine idle {got['idle']:.0f} %)", "-",
              f"keeps up (nothing lost, backlog <= {LAG_S:g} s)",
              "yes" if not got["behind"] else f"no: {busiest(got)}, backlog {got['lag_s']:.1f} s",
              bench.versus([runs], lambda r: sum(r["gateways"]) / len(r["gateways"]),
                           fmt=lambda v: f"{100 * v:.0f} %"))
    for build in bench.builds:
        if runs.get(build):
            bench.cpu_row(f"fleet: {shape}", build.label, [runs[build]["cpu"]])


def summary_rows(bench, counts, results):
    """The largest N carried with zero loss, the first N behind, and the most the cluster
    delivered in a run (its ceiling, once a run is behind)."""
    def largest(build):
        ok = [n for n in counts if results[n].get(build) and max(results[n][build]["lost"]) == 0]
        return max(ok) if ok else 0

    def first_behind(build):
        return next((n for n in counts if results[n].get(build) and
                     results[n][build]["behind"]), 0)

    def most(build):
        runs = [(sum(results[n][build]["rates"]), n) for n in counts if results[n].get(build)]
        return max(runs) if runs else None

    bench.row(f"fleet: largest N carried with zero loss (N = {', '.join(map(str, counts))})",
              f"{largest(bench.build)}", "-", "-", "-", "-",
              bench.versus([{b: largest(b) for b in bench.builds}], lambda v: v,
                           fmt="{}".format))
    behind = first_behind(bench.build)
    got = results[behind][bench.build] if behind else None
    bench.row(f"fleet: first N behind the offered load (a loss, or a backlog over {LAG_S:g} s)",
              f"{behind} ({busiest(got)}, machine idle {got['idle']:.0f} %)" if got else
              f"none up to {counts[-1]}", "-", "-", "-", "-",
              bench.versus([{b: first_behind(b) for b in bench.builds}], lambda v: v,
                           fmt=lambda v: f"{v}" if v else "none"))
    rate, n = most(bench.build)
    got = results[n][bench.build]
    bench.row("fleet: the most tag updates/s the cluster delivered in a run (sum of the "
              "subscribers; its ceiling once the run is behind)",
              f"{rate:,.0f} at N = {n} ({' / '.join(f'{r:,.0f}' for r in got['rates'])} per "
              f"node; {'behind: the ceiling' if got['behind'] else 'not behind: no ceiling'})",
              f"{3 * got['offered']:,.0f} offered", f"{rate / (3 * got['offered']):.2f}", "-",
              "-", bench.versus([{b: most(b) for b in bench.builds}], lambda v: v[0]))


def run(bench):
    print("[18] a fleet: N gateways in namespaces of their own -> three-node ejabberd",
          flush=True)
    why = unavailable()
    if why:
        raise RuntimeError(f"scenario 18: {why}")
    counts = QUICK_COUNTS if bench.quick else COUNTS
    duration = 3 if bench.quick else 10
    results = {}
    start = time.monotonic()
    with netns.Segment(f"e2mb{os.getpid()}", SEGMENT) as segment:
        members = [segment.add_member()[0] for _ in range(max(counts))]
        with EjabberdCluster(segment.hub) as cluster:
            print(f"    cluster of {len(cluster.nodes)} nodes up in "
                  f"{time.monotonic() - start:.0f} s", flush=True)
            for count in counts:
                results[count] = bench.per_build(0, lambda build: fleet_run(
                    bench, segment, members, cluster, build, count, duration))
    for count in counts:
        fleet_rows(bench, count, results[count])
    summary_rows(bench, counts, results)
