"""Measurements more than one scenario takes: bare Paho's rate, a gateway's rate under a
load, the zero-loss rate of a receiver, and how rounds are written in a row."""

import contextlib
import socket
import subprocess

from benchlib.builds import NotInBuild
from benchlib.cpu import PERIOD_S, CpuSampler
from benchlib.util import (HOST, PAHO_WINDOW, TAGS, consumed_list, free_port, last_json,
                           offered_datagrams, stop, tool)


class Measures:
    def zero_loss_ceiling(self, trial, steps, start, scenario):
        """The highest offered rate `trial(rate, n)` passes with zero loss: doubling from
        `start`, then `steps` bisections. The quick form checks that it works, not the figure:
        one trial, at 4 x `start` (the rate achieved when it passes, else 0). Returns (rate
        achieved, trials)."""
        ok_rate, bad, rate, trials = 0.0, None, start * (4 if self.quick else 1), 0
        while rate <= 3200000 and trials < 10:
            trials += 1
            ok, achieved = trial(rate, trials)
            if self.quick:
                return (achieved if ok else 0.0), trials
            if not ok:
                bad = rate
                break
            ok_rate = max(ok_rate, achieved)
            if achieved < 0.9 * rate:  # the generator itself cannot go faster
                self.notes.append(f"{scenario}: the load generator topped out at "
                                  f"{achieved:.0f} datagrams/s")
                return ok_rate, trials
            rate *= 2
        good = rate / 2 if bad else rate
        for _ in range(steps if bad else 0):
            mid = (good + bad) / 2
            trials += 1
            ok, achieved = trial(mid, trials)
            if ok:
                good, ok_rate = mid, max(ok_rate, achieved)
            else:
                bad = mid
        return ok_rate, trials

    def rounds_label(self, which="median"):
        return f", {which} of {self.rounds} paired rounds" if self.rounds > 1 else ""

    @staticmethod
    def ratios_note(results):
        if len(results) < 2:
            return ""
        return " (rounds: " + ", ".join(f"{r[0]:.2f}" for r in results) + ")"

    @staticmethod
    def values_note(values):
        if len(values) < 2:
            return ""
        return "; rounds: " + ", ".join(f"{v:,.0f}" for v in values)

    def sample_period(self):
        """CPU samples 0.25 s apart, closer in short runs (ten at least in a load)."""
        return min(PERIOD_S, self.d / 10)

    def broker_pid(self):
        return next(proc.pid for proc, port in self.brokers.values() if port == self.broker_port)

    def run_load(self, args, timeout, role, groups, sample, threads=()):
        """Runs `args`, a run's load, to its end: (its JSON line, a CpuSampler of it as `role`,
        of `groups` ({role: [pid, ...]}) and of the broker, or None unless `sample`; the roles
        in `threads` sampled thread by thread too)."""
        proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.procs.append(proc)
        sampler = None
        if sample:
            sampler = CpuSampler({**groups, role: [proc.pid], "broker": [self.broker_pid()]},
                                 self.sample_period(), threads).start()
        try:
            out, err = proc.communicate(timeout=timeout)
        finally:
            if sampler:
                sampler.stop()
        if proc.returncode != 0:
            raise RuntimeError(f"{args[0]} failed ({proc.returncode}): {err[-500:]}")
        return last_json(out), sampler

    def paho_run(self, qos, topics=TAGS, sample=False):
        """Bare Paho as fast as its window allows: (messages/s counted, its CPU per
        publication or None)."""
        counter = self.start_counter("p/+/+", qos)
        pub, sampler = self.run_load(
            [tool("paho_publisher"), "--url", f"tcp://{HOST}:{self.broker_port}", "--window",
             str(PAHO_WINDOW), "--qos", str(qos), "--duration", str(self.d), "--topics",
             str(topics)], self.d + 60, "publisher", {"subscriber": [counter.pid]}, sample)
        got = self.finish(counter)
        print(f"    paho qos{qos} ({topics} topics): published {pub['published']} received "
              f"{got['messages']} at {got['rate']:.0f}/s", flush=True)
        return got["rate"], sampler and sampler.per_publication(got["rate"], self.d)

    def paho_ceiling(self, qos, topics=TAGS):
        return self.paho_run(qos, topics)[0]

    def paho_with_input(self, qos, topics, exchanges, tags, change, datagrams):
        """Bare Paho again, with the gateway's datagram input running beside it: the load
        generator at `datagrams`/s to a bare recvmmsg sink. On two cores that input takes a
        share of the machine that bare Paho alone never pays. The input outlasts Paho's run by
        1 s, and the sink stops 1 s after it (0.5 s, and the counter's idle time, in the quick
        form)."""
        port = free_port(socket.SOCK_DGRAM)
        sink = self.start_sink(port, "--idle-ms", self.idle_ms if self.quick else 1000,
                               "--max-s", self.d + 30)
        gen = self.start_generator(port, exchanges, datagrams, self.d + (0.5 if self.quick else 1),
                                   change=change, tags=tags)
        rate = self.paho_ceiling(qos, topics=topics)
        gen.communicate(timeout=self.d + 60)
        sink.communicate(timeout=self.d + 60)
        return rate

    def rate_counter(self, qos, batch, sparkplug):
        if sparkplug:
            return self.start_counter("spBv1.0/bench/DDATA/#", qos, extra=["--sparkplug"])
        if batch:
            return self.start_counter("b/+/_values", qos, extra=["--batch"])
        return self.start_counter("b/+/+", qos)

    def gateway_rate(self, name, qos, change, ceiling, batch=False, exchanges=1, sparkplug=False,
                     tags=TAGS, build=None, sample=False, datagrams=None, threads=False,
                     scaled=False, prometheus=0, during=None):
        """`build`'s gateway offered 1.5 x `ceiling` tag updates/s (or `datagrams`/s): the
        counter's JSON, with the run's CPU per publication as "cpu" when `sample` (the
        gateway's thread by thread too with `threads`); `scaled`: every tag with an engineering
        scale; `prometheus`: its listener's port; `during`: a context the load runs in,
        entered once the gateway is online."""
        gw, udp_port = self.launch_gateway(name, consumed_list(exchanges, tags), qos, batch=batch,
                                           sparkplug=sparkplug, build=build, scaled=scaled,
                                           prometheus=prometheus)
        counter = self.rate_counter(qos, batch, sparkplug)
        per_datagram = max(1, round(change * tags))
        try:
            with during or contextlib.nullcontext():
                gen, sampler = self.run_load(
                    self.generator_args(udp_port, exchanges,
                                        datagrams or offered_datagrams(ceiling, change, tags),
                                        duration=self.d, change=change, tags=tags),
                    self.d + 60, "load generator",
                    {"gateway": [gw.pid], "subscriber": [counter.pid]}, sample,
                    ("gateway",) if threads else ())
        except NotInBuild:
            stop(counter)
            stop(gw)
            raise
        got = self.finish(counter)
        got["cpu"] = sampler and sampler.per_publication(got["rate"], self.d)
        # For the log line only (uns: false has no metrics topic).
        m = None if sparkplug or self.quick else self.metrics(name)
        stop(gw)
        print(f"    gateway {name}: offered {gen['rate']:.0f} datagrams/s x {per_datagram} tags; "
              f"received {got['messages']} msgs, {got['updates']} updates at "
              f"{got['update_rate']:.0f}/s; coalesced {m and m.get('publications_coalesced')}",
              flush=True)
        return got

    def gateway_ceiling(self, build, qos, shape, setup):
        """`build`'s per-tag rate at `qos` with `shape` ((exchanges, tags)), every tag changing,
        on the broker `setup` (the one in use): scenario 2's figure of this run (the median
        round), else a short run of scenario 2's kind (offered 1.5 x bare Paho's rate) now."""
        key = ("gw", build.label, qos, shape, setup)
        if key not in self.ceilings:
            paho = ("paho", qos, shape, setup)
            if paho not in self.ceilings:
                self.ceilings[paho] = self.paho_ceiling(qos, topics=shape[0] * shape[1])
            got = self.gateway_rate(f"g14c{qos}", qos, 1.0, self.ceilings[paho],
                                    exchanges=shape[0], tags=shape[1], build=build)
            self.ceilings[key] = got["rate"]
        return self.ceilings[key]

    def split_gateways_rate(self, qos, change, ceiling, exchanges, tags, build=None,
                            sample=False):
        """The tuning a user can set: two gateway processes, each consuming half of the
        exchanges, with its own Paho, its own connection and a load generator of its own at
        half the datagrams one gateway is offered (gateway_rate)."""
        share = exchanges // 2
        firsts = (1, 1 + share)  # each half's first exchange
        gateways = [self.launch_gateway(f"split{i}", consumed_list(share, tags, f), qos,
                                        build=build)
                    for i, f in enumerate(firsts)]
        counter = self.start_counter("b/+/+", qos)
        rate = offered_datagrams(ceiling, change, tags) // 2
        generators = [self.start_generator(port, share, rate, self.d, change=change, tags=tags,
                                           first=f)
                      for f, (_, port) in zip(firsts, gateways)]
        sampler = CpuSampler({"gateway": [g.pid for g, _ in gateways],
                              "load generator": [g.pid for g in generators],
                              "broker": [self.broker_pid()], "subscriber": [counter.pid]},
                             self.sample_period())
        if sample:
            sampler.start()
        for generator in generators:
            generator.communicate(timeout=self.d + 60)
        if sample:
            sampler.stop()
        got = self.finish(counter)
        got["cpu"] = sampler.per_publication(got["rate"], self.d) if sample else None
        for gateway, _ in gateways:
            stop(gateway)
        print(f"    two gateways: received {got['messages']} msgs at {got['rate']:.0f}/s",
              flush=True)
        return got
