"""Scenario 13: failover of a hot-standby pair (docs/redundancy.md). Two units of one pair on
the tuned broker, each fed its own copy of one consumed exchange by a load generator (each unit
must receive the datagrams itself), both producing one exchange to a socket the scenario reads.
Each trial kills the leader (SIGKILL) at T and times T -> the new leader's first datagram and
T -> its first tag publication at a subscriber, beside the broker's round trip measured in the
same trial; the killed unit is then restarted, and stands by for the next trial."""

import os
import signal
import socket
import time

from benchlib.pair_watch import PairWatch, json_field
from benchlib.util import HOST, free_port, median, stop

TAKEOVER_MS, PERIOD_MS = 1000, 100
# The consumed exchange e1: 10 tags, 100 datagrams/s to each unit, `ts` (the load generator's
# send time) changing in every one.
EXCHANGE, TAGS, RATE = 1, 10, 100
PRODUCED = 13
TAG_TOPIC = f"b/e{EXCHANGE}/ts"
ROLE = "b/_gateway/{}/role"
LEADER = "b/_gateway/_pair/{}/leader"
TARGET_MS = TAKEOVER_MS + PERIOD_MS
# Leaderships a trial may try: one the machine's load disturbed (the leader fenced, a second
# producer seen) is not killed, and the trial waits for the next.
TRIES = 3


class Pair:
    """The two units of `build` and their load generators."""

    def __init__(self, bench, build, round_index, sink_port):
        suffix = "" if build.new else "x"
        self.bench, self.build = bench, build
        self.names = (f"g13a{suffix}", f"g13b{suffix}")
        # A pair of its own per round and build: no record of an earlier one is retained.
        pair = f"f13r{round_index}{suffix}"
        self.leader_topic = LEADER.format(pair)
        self.ports, self.configs, self.procs, self.started = {}, {}, {}, {}
        for name in self.names:
            self.ports[name] = free_port(socket.SOCK_DGRAM)
            self.configs[name] = bench.write_config(
                name, consumed=[(EXCHANGE, TAGS)], udp_port=self.ports[name], build=build,
                produced=[(PRODUCED, 1, PERIOD_MS, f"{HOST}:{sink_port}")],
                redundancy={"pair": pair, "takeover_ms": TAKEOVER_MS})
        self.generators = []
        self.disturbed = 0

    def start(self, name):
        self.started[name] = time.time_ns()
        self.procs[name] = self.bench.start_gateway(name, self.configs[name], build=self.build)

    def start_all(self, seconds):
        for name in self.names:
            self.start(name)
        for name in self.names:
            self.generators.append(self.bench.start_generator(
                self.ports[name], 1, RATE, seconds, tags=TAGS, first=EXCHANGE))

    def kill(self, name):
        """SIGKILL: (the instant it was sent, the instant the unit was reaped), ns."""
        proc = self.procs[name]
        sent = time.time_ns()
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=10)
        return sent, time.time_ns()

    def stop(self):
        for proc in list(self.procs.values()) + self.generators:
            stop(proc)

    def roles(self, watch):
        """(leader, standby) by what each unit said last since it started; None otherwise."""
        said = {}
        for name in self.names:
            latest = watch.latest.get(ROLE.format(name))
            if latest and latest[0] >= self.started[name]:
                said[latest[1]] = name
        return (said["leader"], said["standby"]) if set(said) == {"leader", "standby"} else None

    def settle(self, watch, timeout=30):
        """Waits for one unit to lead and the other to stand by: (leader, standby). An earlier
        build whose unit ended or never settled is NotInBuild."""
        try:
            return watch.until(lambda: self.roles(watch), timeout,
                               f"leader and standby among {', '.join(self.names)}")
        except RuntimeError:
            for name, proc in self.procs.items():
                self.build.start_failed(proc, os.path.join(self.bench.tmp, name + ".log"))
            raise


def lead_window(pair, watch, run_s, delay):
    """The pair run for `run_s` s under a settled leader, then `delay` s after its next
    renewal: (leader, standby, the leader's source port, the broker round trips probed, ms), or
    None when the roles changed meanwhile or the datagrams came from more than one source."""
    leader, standby = pair.settle(watch)
    mark = len(watch.datagrams)
    trips = [watch.probe()]
    watch.run_for(run_s)
    trips.append(watch.probe())
    records = len(watch.messages)
    watch.until(lambda: watch.first_message(records, lambda t, p: t == pair.leader_topic and
                                            json_field(p, "id") == leader),
                2 * TAKEOVER_MS / 1000, f"a renewal by {leader}")
    watch.run_for(delay)
    sources = {port for _, port in watch.datagrams[mark:]}
    if len(sources) == 1 and pair.roles(watch) == (leader, standby):
        return leader, standby, sources.pop(), trips
    pair.disturbed += 1
    print(f"    disturbed: {len(sources)} source(s) of datagrams, roles now "
          f"{pair.roles(watch)} (were {leader} leading)", flush=True)
    return None


def takeover(pair, watch, leader, standby, source):
    """Kills `leader`; ms from the kill to what followed: the standby's claim (its first record
    on the pair's topic), its `leader` on its role topic, its first datagram (a source other
    than `leader`'s), and the first tag publication that `leader` cannot have made: a `ts` the
    load generator stamped after `leader` was reaped. `renewal`: the last record on the topic
    before the kill (ms, negative), whoever sent it."""
    renewal = watch.latest.get(pair.leader_topic)
    datagrams, messages = len(watch.datagrams), len(watch.messages)
    killed, reaped = pair.kill(leader)

    def seen():
        got = (
            watch.first_message(messages, lambda t, p: t == pair.leader_topic and
                                json_field(p, "id") == standby),
            watch.first_message(messages, lambda t, p: t == ROLE.format(standby) and
                                p == "leader"),
            watch.first_datagram(datagrams, lambda at, port: port != source and at > killed),
            watch.first_message(messages, lambda t, p: t == TAG_TOPIC and
                                (json_field(p, "value") or 0) > reaped),
        )
        return got if all(got) else None

    claim, role, datagram, publication = watch.until(
        seen, TAKEOVER_MS / 1000 + 10, f"takeover by {standby} after {leader} was killed")
    return {"renewal": (renewal[0] - killed) / 1e6 if renewal else None,
            "claim": (claim[0] - killed) / 1e6, "leader": (role[0] - killed) / 1e6,
            "datagram": (datagram[0] - killed) / 1e6,
            "publication": (publication[0] - killed) / 1e6}


def one_trial(pair, watch, run_s, phase, index):
    """A takeover from a leader killed `phase` (0..1) of a renewal interval after a renewal."""
    window = None
    for _ in range(TRIES):
        window = lead_window(pair, watch, run_s, phase * TAKEOVER_MS / 4 / 1000)
        if window:
            break
    if not window:
        raise RuntimeError(f"scenario 13: {TRIES} leaderships in a row disturbed")
    leader, standby, source, trips = window
    got = takeover(pair, watch, leader, standby, source)
    got["round_trips"] = trips
    renewal = "-" if got["renewal"] is None else f"{got['renewal']:.0f}"
    print(f"    {pair.build.label}, trial {index + 1}: {leader} killed (last record {renewal} ms); "
          f"{standby}: claim +{got['claim']:.0f}, leader +{got['leader']:.0f}, datagram "
          f"+{got['datagram']:.0f}, publication +{got['publication']:.0f} ms; round trips "
          + ", ".join(f"{t:.2f}" for t in trips) + " ms", flush=True)
    # The killed unit comes back and stands by: the next trial kills the other one.
    pair.start(leader)
    return got


def run_round(bench, watch, build, phases, round_index):
    pair = Pair(bench, build, round_index, watch.port)
    run_s = 1.0 if bench.quick else 2.0
    out = []
    try:
        # The generators outlast the round's every bounded wait; stopped with the round.
        pair.start_all(seconds=120 + 60 * len(phases))
        for phase in phases:
            out.append(one_trial(pair, watch, run_s, phase, len(out)))
    finally:
        pair.stop()
    if pair.disturbed:
        bench.notes.append(f"scenario 13 ({build.label}, round {round_index + 1}): "
                           f"{pair.disturbed} leadership(s) disturbed, not killed")
    return out


def pooled(rounds, key):
    """`key` of every trial of `rounds` (one build's list of trials per round)."""
    return [t[key] for trials in rounds for t in trials if t[key] is not None]


def spread(values, fmt="{:,.0f}"):
    return f"{fmt.format(median(values))} (max {fmt.format(max(values))})"


def rows(bench, results):
    mine = [r[bench.build] for r in results]
    count = len(pooled(mine, "datagram"))
    setting = (f"takeover_ms {TAKEOVER_MS}, produced every {PERIOD_MS} ms, {count} trials" +
               (f" over {bench.rounds} rounds" if bench.rounds > 1 else ""))

    def versus(key):
        return bench.versus(results, lambda trials: median([t[key] for t in trials]),
                            shown=lambda old: spread(pooled(old, key)))

    produced = pooled(mine, "datagram")
    stages = ", ".join(f"{what} {median(pooled(mine, key)):+,.0f}" for what, key in (
        ("last record heard", "renewal"), ("claim", "claim"), ("role leader", "leader")))
    bench.row(f"failover: SIGKILL of the leader -> first datagram of the new leader, ms "
              f"({setting})", f"{spread(produced)}; medians: {stages}", "-", "-",
              f"max <= {TARGET_MS:,} ms (takeover_ms + period)",
              "yes" if max(produced) <= TARGET_MS else "no", versus("datagram"))
    published = pooled(mine, "publication")
    trips = [t for trials in mine for trial in trials for t in trial["round_trips"]]
    target = TARGET_MS + median(trips)
    bench.row(f"failover: SIGKILL of the leader -> first tag publication of the new leader at a "
              f"subscriber, ms ({setting})", spread(published),
              f"{spread(trips, '{:.2f}')} ms broker round trip (probe publish -> subscriber, "
              f"{len(trips)} probes)", "-",
              f"max <= {target:,.0f} ms (takeover_ms + period + round trip)",
              "yes" if max(published) <= target else "no", versus("publication"))


def run(bench):
    print("[13] failover of a hot-standby pair: SIGKILL of the leader -> the new leader's first "
          "datagram and tag publication", flush=True)
    bench.use_broker("tuned")
    total = 3 if bench.quick else 20
    # Where in the renewal interval each trial kills the leader, evenly spread: the time from
    # the last renewal the standby heard to the kill makes most of a takeover's spread, and a
    # fixed window would land on the same point every time. Each round spans the interval.
    phases = [(k + 0.5) / total for k in range(total)]
    watch = PairWatch(bench, [ROLE.format("+"), LEADER.format("+"), TAG_TOPIC])
    try:
        results = [bench.per_build(r, lambda b, r=r: run_round(
            bench, watch, b, phases[r::bench.rounds], r)) for r in range(bench.rounds)]
    finally:
        watch.close()
    rows(bench, results)
