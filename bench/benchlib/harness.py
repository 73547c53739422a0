"""The run's state and the parts the scenarios call: Bench."""

import tempfile

from benchlib.builds import Build, NotInBuild, in_order
from benchlib.gateways import Gateways
from benchlib.measures import Measures
from benchlib.processes import Processes
from benchlib.report import Report
from benchlib.util import GATEWAY


class Bench(Processes, Gateways, Measures, Report):
    def __init__(self, quick, only, against=None, rounds=0):
        """against: (label, gateway binary) of an earlier build to run beside this one;
        rounds: the repeated scenarios' paired rounds, 0 for the default."""
        self.quick = quick
        self.only = only
        # Scenarios whose figures the host's other work moves most (2, 3, 5, 7, and the loss of
        # 1) repeat their baseline and gateway runs in turn, and report the median round.
        self.rounds = rounds or (1 if quick else 3)
        self.tmp = tempfile.mkdtemp(prefix="eip2mqtt-bench-")
        self.rows = []
        self.cpu_rows = []  # (figure, run, [CpuSampler.per_publication of each round])
        self.notes = []
        self.brokers = {}  # setup -> (process, port)
        self.broker_port = 0  # the broker the next step talks to (use_broker)
        self.procs = []
        self.counter_seq = 0
        # The quick form checks that everything works, not figures: shorter runs, and a
        # counter that stops sooner once the messages stop.
        self.d = 0.4 if quick else 5  # seconds per throughput run
        self.idle_ms = 400 if quick else 1500
        # Scenario 2's figures later scenarios take as their load: bare Paho's per-tag rate
        # (by QoS) and the gateway's (by ("gw", QoS)), 1 x 100 tags on the tuned broker.
        self.ceilings = {}
        # Bare Paho's rate by (QoS, broker), 1 x 100 tags: the machine, in the report.
        self.paho_rates = {}
        self.build = Build("this build", GATEWAY, new=True)
        self.against = Build(against[0], against[1], new=False) if against else None
        self.builds = [self.build] + ([self.against] if self.against else [])

    def wanted(self, n):
        return not self.only or n in self.only

    def per_build(self, round_index, measure):
        """measure(build) for each build, in round `round_index`'s order: {build: its result},
        None for an earlier build that cannot run it."""
        out = {}
        for build in in_order(self.builds, round_index):
            try:
                out[build] = measure(build)
            except NotInBuild as e:
                print(f"    not in {build.label}: {e.reason}", flush=True)
                # "FILE:LINE:COLUMN: error: WHAT" from `check`: WHAT is the same in every run.
                note = f"not in {build.label}: {e.reason.split(': error: ')[-1]}"
                if note not in self.notes:
                    self.notes.append(note)
                out[build] = None
        return out
