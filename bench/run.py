#!/usr/bin/env python3
"""The benchmark driver behind bench/run.sh; see bench/README.md.

Starts its own Mosquitto on a free loopback port, runs every scenario against the gateway built
from this repository and against its same-run baseline (and, with --against-binary, against an
earlier build in alternating rounds), and writes one markdown table to bench/results/latest.md
(also printed). Every wait is bounded in time; only 127.0.0.1 is used (and, by scenario 18,
network namespaces it makes itself). The harness is in bench/benchlib/, one module per
scenario in bench/scenarios/.
"""

import argparse
import os
import sys
import time
import traceback

from benchlib import node_red
from benchlib.harness import Bench
from benchlib.util import GATEWAY, tool
from scenarios import (s01_udp, s02_s03_publications, s04_batch, s05_latency, s06_memory,
                       s07_periods, s08_overload, s09_write_latency, s10_store_and_forward,
                       s11_commands, s12_dissector, s13_failover, s14_overload_rate,
                       s15_topic_aliases, s16_status_page, s17_broker_move, s18_fleet)

# (the scenario numbers a module answers to in --only, its module), in the order they run:
# later scenarios take their load from scenario 2's figures.
SCENARIOS = (
    ((1,), s01_udp),
    ((2, 3), s02_s03_publications),
    ((4,), s04_batch),
    ((5,), s05_latency),
    ((6,), s06_memory),
    ((7,), s07_periods),
    ((8,), s08_overload),
    ((9,), s09_write_latency),
    ((10,), s10_store_and_forward),
    ((11,), s11_commands),
    ((12,), s12_dissector),
    ((13,), s13_failover),
    ((14,), s14_overload_rate),
    ((15,), s15_topic_aliases),
    ((16,), s16_status_page),
    ((17,), s17_broker_move),
    ((18,), s18_fleet),
)
# Scenarios that run only when --only names them, never in a run of every scenario: 18 needs
# root, network namespaces and ejabberd (and the quick run's test counts the rows of a run of
# every scenario).
ONLY_WHEN_ASKED = {18}


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="short runs, to check it works")
    parser.add_argument("--only", default="",
                        help="comma-separated scenario numbers (1-18; 18 runs only when named)")
    parser.add_argument("--rounds", type=int, default=0, metavar="N",
                        help="paired rounds of the repeated scenarios (default 3, 1 with --quick)")
    parser.add_argument("--against-binary", default="", metavar="PATH",
                        help="an earlier build's eip2mqtt, run beside this one in every "
                             "scenario (bench/run.sh --against REV builds it)")
    parser.add_argument("--against-label", default="", metavar="NAME",
                        help="how the report names that build (default: its path)")
    return parser.parse_args()


def command_line(args):
    """The run as bench/run.sh's command line, for the report."""
    return ("bench/run.sh" + (" --quick" if args.quick else "") +
            (f" --only {args.only}" if args.only else "") +
            (f" --rounds {args.rounds}" if args.rounds else "") +
            (f" --against {args.against_label or args.against_binary}"
             if args.against_binary else ""))


def check_programs(args, only):
    if not only or 14 in only:  # the Node-RED peer row: installed by tools/install-deps.sh
        node_red.require_installed()
    if 18 in only and s18_fleet.unavailable():  # namespaces and an ejabberd cluster
        sys.exit(f"scenario 18: {s18_fleet.unavailable()}")
    if not only or 16 in only:  # the page's render: chromium and puppeteer-core, as its test
        for path in (s16_status_page.CHROMIUM, s16_status_page.PUPPETEER):
            if not os.path.exists(path):
                sys.exit(f"missing {path}: run tools/install-deps.sh")
    for path in (GATEWAY, tool("load_generator"), tool("mqtt_counter"), tool("yaml_parse"),
                 tool("write_latency")) + ((args.against_binary,) if args.against_binary else ()):
        if not os.access(path, os.X_OK):
            sys.exit(f"missing {path}: run bench/run.sh, which builds first")


def run_scenarios(bench):
    """Every wanted scenario; one that fails is noted and the others still run, so that a
    run of an hour keeps what it measured. The scenarios that failed, by number."""
    failed = []
    for numbers, scenario in SCENARIOS:
        if any(n in bench.only if n in ONLY_WHEN_ASKED else bench.wanted(n) for n in numbers):
            label = ",".join(map(str, numbers))
            start = time.monotonic()
            try:
                scenario.run(bench)
            except Exception as e:  # noqa: BLE001 (any failure: reported, and the run fails)
                traceback.print_exc()
                why = (str(e).splitlines() or [type(e).__name__])[0]
                bench.notes.append(f"scenario {label} stopped before its last row: {why}")
                failed.append(label)
            print(f"    (scenario {label}: {time.monotonic() - start:.0f} s)", flush=True)
    if not bench.paho_rates:  # scenario 2 did not run: the machine is still named by them
        for qos in (0, 1):
            bench.paho_rates[(qos, "tuned broker")] = bench.paho_ceiling(qos)
    return failed


def main():
    args = parse_args()
    only = {int(x) for x in args.only.split(",") if x}
    if args.rounds < 0:
        sys.exit("--rounds: a count of rounds, at least 1")
    check_programs(args, only)
    against = None
    if args.against_binary:
        against = (args.against_label or args.against_binary, args.against_binary)
    bench = Bench(args.quick, only, against, args.rounds)
    try:
        bench.start_broker()
        failed = run_scenarios(bench)
    finally:
        bench.close()
    bench.report(command_line(args))
    if failed:
        sys.exit(f"bench: scenario {', '.join(failed)} failed (the notes of the report say how)")


if __name__ == "__main__":
    main()
