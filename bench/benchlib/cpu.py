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


def process_ticks(pid):
    """utime + stime of every thread of `pid` (0 once it is gone)."""
    total = 0
    try:
        tasks = os.listdir(f"/proc/{pid}/task")
    except OSError:
        return 0
    for task in tasks:
        try:
            with open(f"/proc/{pid}/task/{task}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        total += int(fields[11]) + int(fields[12])  # utime, stime: fields 14 and 15 of stat
    return total


def machine_ticks():
    """(idle, all) ticks of the whole machine, every CPU together; iowait counts as idle."""
    with open("/proc/stat") as f:
        fields = [int(x) for x in f.readline().split()[1:9]]
    return fields[3] + fields[4], sum(fields)


class CpuSampler:
    """Samples the CPU time of groups of processes ({role: [pid, ...]}) on a thread of its
    own, from `start()` to `stop()`, every `period_s`."""

    def __init__(self, groups, period_s=PERIOD_S):
        self.groups = {role: list(pids) for role, pids in groups.items() if pids}
        self.period_s = period_s
        self.samples = []  # (monotonic s, {role: ticks}, idle ticks, all ticks)
        self.started = None
        self._done = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)

    def _sample(self):
        idle, total = machine_ticks()
        ticks = {role: sum(process_ticks(p) for p in pids) for role, pids in self.groups.items()}
        self.samples.append((time.monotonic(), ticks, idle, total))

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
        the machine idle, "rate": rate} over the loaded part of a run whose load lasted
        `load_s` from start(), `rate` publications/s being counted; None without two samples
        in it."""
        begin = self.started + min(SETTLE_S, load_s / 4)
        end = self.started + load_s - min(TAIL_S, load_s / 4)
        inside = [s for s in self.samples if begin <= s[0] <= end]
        if len(inside) < 2:  # the sampler held up by a loaded machine: the whole load instead
            inside = [s for s in self.samples if s[0] <= self.started + load_s]
        if len(inside) < 2 or rate <= 0:
            return None
        (t0, ticks0, idle0, all0), (t1, ticks1, idle1, all1) = inside[0], inside[-1]
        publications = rate * (t1 - t0)
        out = {role: max(0, ticks1[role] - ticks0[role]) * TICK_S * 1e6 / publications
               for role in self.groups}
        busy = (all1 - all0) - (idle1 - idle0)
        out["machine"] = busy * TICK_S * 1e6 / publications
        out["idle"] = 100.0 * (idle1 - idle0) / (all1 - all0) if all1 > all0 else 0.0
        out["rate"] = rate
        return out
