"""CPU time per publication of each process of a run, and of the machine: every 0.25 s (more
often in a short run), each process's CPU time summed over its threads
(/proc/PID/task/*/stat, utime + stime) and the machine's idle time (/proc/stat), over the
loaded part of the run. Unlike a rate, this figure does not depend on what else the machine
runs."""

import os
import threading
import time

TICK_S = 1.0 / os.sysconf("SC_CLK_TCK")
PERIOD_S = 0.25
# The loaded part of a run: from 1 s after its load started (every process out of idle) to
# 0.5 s before the load ends; a quarter of the load at each end when the load is short.
SETTLE_S, TAIL_S = 1.0, 0.5


def thread_ticks(pid):
    """{thread name: utime + stime} of the threads of `pid`, threads of one name summed
    (empty once it is gone)."""
    out = {}
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return out
    for task in tasks:
        try:
            with open(f"/proc/{pid}/task/{task}/stat") as f:
                head, tail = f.read().rsplit(")", 1)
            fields = tail.split()
            name = head.split("(", 1)[1]
        except (OSError, IndexError):
            continue
        # utime, stime: fields 14 and 15 of stat
        out[name] = out.get(name, 0) + int(fields[11]) + int(fields[12])
    return out


def process_ticks(pid):
    """utime + stime of every thread of `pid` (0 once it is gone)."""
    return sum(thread_ticks(pid).values())


def machine_ticks():
    """(idle, all) ticks of the whole machine, every CPU together; iowait counts as idle."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:9]]
    return fields[3] + fields[4], sum(fields)


class CpuSampler:
    """Samples the CPU time of groups of processes ({role: [pid, ...]}) on a thread of its
    own, from `start()` to `stop()`, every `period_s`; the roles named in `threads` thread by
    thread too (by thread name)."""

    def __init__(self, groups, period_s=PERIOD_S, threads=()):
        self.groups = {role: list(pids) for role, pids in groups.items() if pids}
        self.period_s = period_s
        self.threads = [role for role in threads if role in self.groups]
        # (monotonic s, {role: ticks}, idle ticks, all ticks, {role: {thread name: ticks}})
        self.samples = []
        self.started = None
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _sample(self):
        idle, total = machine_ticks()
        by_thread = {}
        for role in self.threads:
            named = by_thread.setdefault(role, {})
            for pid in self.groups[role]:
                for name, t in thread_ticks(pid).items():
                    named[name] = named.get(name, 0) + t
        ticks = {role: sum(by_thread[role].values()) if role in by_thread else
                 sum(process_ticks(p) for p in pids) for role, pids in self.groups.items()}
        self.samples.append((time.monotonic(), ticks, idle, total, by_thread))

    def _run(self):
        while not self._done.is_set():
            self._sample()
            self._done.wait(self.period_s)

    def start(self):
        self.started = time.monotonic()
        self._thread.start()
        return self

    def stop(self):
        self._done.set()
        self._thread.join(timeout=5)

    def per_publication(self, rate, load_s):
        """{role: us per publication, "machine": us of busy CPU per publication, "idle": % of
        the machine idle, "rate": rate, and per role sampled by thread "ROLE threads": {thread
        name: us per publication}} over the loaded part of a run whose load lasted
        `load_s` from start(), `rate` publications/s being counted; None without two samples
        in it."""
        begin = self.started + min(SETTLE_S, load_s / 4)
        end = self.started + load_s - min(TAIL_S, load_s / 4)
        inside = [s for s in self.samples if begin <= s[0] <= end]
        if len(inside) < 2:  # the sampler held up by a loaded machine: the whole load instead
            inside = [s for s in self.samples if s[0] <= self.started + load_s]
        if len(inside) < 2 or rate <= 0:
            return None
        (t0, ticks0, idle0, all0, threads0), (t1, ticks1, idle1, all1, threads1) = \
            inside[0], inside[-1]
        publications = rate * (t1 - t0)

        def us(ticks):
            return max(0, ticks) * TICK_S * 1e6 / publications

        out = {role: us(ticks1[role] - ticks0[role]) for role in self.groups}
        for role in self.threads:
            before = threads0.get(role, {})
            out[role + " threads"] = {name: us(t - before.get(name, 0))
                                      for name, t in threads1.get(role, {}).items()}
        busy = (all1 - all0) - (idle1 - idle0)
        out["machine"] = busy * TICK_S * 1e6 / publications
        out["idle"] = 100.0 * (idle1 - idle0) / (all1 - all0) if all1 > all0 else 0.0
        out["rate"] = rate
        return out
