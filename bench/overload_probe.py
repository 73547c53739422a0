#!/usr/bin/env python3
"""Not a scenario: where a publication's cost goes under overload, build against build.

The reference overload (100 exchanges x (ts lint + 10 dints), every tag changing, 6,000
datagrams/s by default, QoS 1, retain off) against Debian's default Mosquitto (`mosquitto -p
PORT`, its own, on a free loopback port), one mqtt_counter on `b/+/+`. Each build runs once per
round, in alternating order. Over 3 s of the loaded part it reads, per publication counted:
the CPU time of each gateway thread and of the broker, counter and load generator
(/proc/PID/task/*/stat), and the TCP segments the gateway's broker connection sent and
received (`ss -tin`); with --syscalls, the system calls of each gateway thread (`perf stat`).
Then the medians per build and the paired ratios of every build to the first.

    bench/overload_probe.py new=build-bench/eip2mqtt old=PATH/eip2mqtt --rounds 8
    bench/overload_probe.py a=build-bench/eip2mqtt b=build-bench/eip2mqtt \
        --mqtt 'b=describe_payloads: false' --tuned    # one binary, a setting apart

Needs bench/run.sh's build tree (build-bench, or EIP2MQTT_BENCH_BUILD) for the instruments.
"""

import argparse
import json
import os
import socket
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchlib.processes import tuned_broker_config  # noqa: E402
from benchlib.util import BUILD, free_port  # noqa: E402

TOOLS = os.path.join(BUILD, "bench")
WINDOW_S = 3.0


def ticks(pid):
    """CPU ticks (utime + stime) of each thread of `pid`, by thread name."""
    out = {}
    for tid in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{tid}/comm") as f:
                comm = f.read().strip()
            with open(f"/proc/{pid}/task/{tid}/stat") as f:
                fields = f.read().rsplit(")", 1)[1].split()
        except OSError:
            continue
        out[comm] = out.get(comm, 0) + int(fields[11]) + int(fields[12])
    return out


def segments(pid, broker_port):
    """data segments out and in of `pid`'s connections to the broker."""
    text = subprocess.run(["ss", "-tinpH", "state", "established", f"( dport = :{broker_port} )"],
                          capture_output=True, text=True, timeout=10).stdout.splitlines()
    out = {"data_segs_out": 0, "data_segs_in": 0}
    for i, line in enumerate(text):
        if f"pid={pid}," not in line:
            continue
        for token in " ".join(text[i:i + 2]).split():
            key, _, value = token.partition(":")
            if key in out and value.isdigit():
                out[key] += int(value)
    return out


def config(path, name, state, broker_port, udp_port, mqtt_extra=()):
    lines = [f"gateway: {{ id: {name}, state_dir: {state}, log_level: warn }}",
             "mqtt:", f"  url: tcp://127.0.0.1:{broker_port}", "  base_topic: b", "  qos: 1",
             "  retain: false", *(f"  {line}" for line in mqtt_extra),
             f"eip: {{ bind: 127.0.0.1, port: {udp_port} }}", "exchanges:"]
    for e in range(1, 101):
        lines += [f"  - name: e{e}", "    direction: consume", "    producer_id: 10.0.0.1",
                  f"    exchange_id: {e}", "    length: 48", "    period_ms: 1000",
                  "    timeout_ms: 0", f"    topic: e{e}", "    tags:",
                  '      - { name: ts, address: "0.0", type: lint }']
        lines += [f'      - {{ name: t{t}, address: "{4 + 4 * t}.0", type: dint }}'
                  for t in range(1, 11)]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def wait_for(predicate, seconds, what):
    deadline = time.monotonic() + seconds
    while not predicate():
        if time.monotonic() > deadline:
            raise RuntimeError(f"timed out waiting for {what}")
        time.sleep(0.05)


def listening(port):
    try:
        socket.create_connection(("127.0.0.1", port), 0.2).close()
        return True
    except OSError:
        return False


def sample(procs, gateway, broker_port):
    return ({k: ticks(p.pid) for k, p in procs.items()}, segments(gateway.pid, broker_port))


def one_run(args, tmp, broker, broker_port, name, label, binary):
    state = os.path.join(tmp, name)
    os.makedirs(state)
    udp_port = free_port(socket.SOCK_DGRAM)
    path = os.path.join(tmp, name + ".yaml")
    config(path, name, state, broker_port, udp_port, args.mqtt_extra.get(label, ()))
    log = open(os.path.join(tmp, name + ".log"), "w")
    procs = {"gateway": subprocess.Popen([binary, "run", "-c", path], stdout=log, stderr=log),
             "broker": broker}
    try:
        subprocess.run(["mosquitto_sub", "-p", str(broker_port), "-W", "20", "-C", "1", "-t",
                        f"b/_gateway/{name}/state"], capture_output=True, timeout=30)
        ready = os.path.join(tmp, name + ".ready")
        procs["counter"] = subprocess.Popen(
            [f"{TOOLS}/mqtt_counter", "--port", str(broker_port), "--filter", "b/+/+", "--qos",
             "1", "--max-s", str(args.seconds + 30), "--idle-ms", "1500", "--ready-file", ready,
             "--id", "c" + name], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        wait_for(lambda: os.path.exists(ready), 10, "the counter")
        procs["generator"] = subprocess.Popen(
            [f"{TOOLS}/load_generator", "--port", str(udp_port), "--exchanges", "100", "--tags",
             "11", "--rate", str(args.rate), "--duration", str(args.seconds), "--change", "1.0"],
            stdout=subprocess.DEVNULL)
        time.sleep(2.0)  # past the first publication of every tag: the steady overload
        before = sample(procs, procs["gateway"], broker_port)
        syscalls = syscall_counts(procs["gateway"].pid, tmp, name) if args.syscalls else None
        if syscalls is None:
            time.sleep(WINDOW_S)
        after = sample(procs, procs["gateway"], broker_port)
        procs["generator"].wait(timeout=args.seconds + 10)
        got = json.loads(procs["counter"].communicate(timeout=args.seconds + 40)[0]
                         .strip().splitlines()[-1])
    finally:
        for key, p in procs.items():
            if key != "broker" and p.poll() is None:
                p.terminate()
                p.wait(10)
    return summarise(got["rate"], before, after, syscalls, os.path.basename(binary)[:15])


def syscall_counts(pid, tmp, name):
    """System calls of each gateway thread over WINDOW_S (perf stat --per-thread)."""
    out = os.path.join(tmp, name + ".perf")
    events = ",".join(f"syscalls:sys_enter_{c}" for c in
                      ("writev", "recvfrom", "poll", "futex", "setsockopt", "recvmmsg"))
    subprocess.run(["perf", "stat", "-x", ",", "--per-thread", "-e", events, "-p", str(pid),
                    "-o", out, "--", "sleep", str(WINDOW_S)], stderr=subprocess.DEVNULL,
                   timeout=WINDOW_S + 20)
    counts = {}
    with open(out) as f:
        for line in f:
            fields = line.strip().split(",")
            if len(fields) > 3 and fields[1].strip().isdigit():
                thread = fields[0].rsplit("-", 1)[0]
                call = fields[3].replace("syscalls:sys_enter_", "")
                counts[(thread, call)] = counts.get((thread, call), 0) + int(fields[1])
    return counts


def summarise(rate, before, after, syscalls, loop_name):
    publications = rate * WINDOW_S
    us = 1e6 / os.sysconf("SC_CLK_TCK") / publications if publications else 0
    (cpu0, seg0), (cpu1, seg1) = before, after
    # The loop thread has the binary's name: "loop" in every build.
    threads = {("loop" if t == loop_name else t): round((n - cpu0["gateway"].get(t, 0)) * us, 1)
               for t, n in cpu1["gateway"].items()}
    others = {k: round((sum(cpu1[k].values()) - sum(cpu0[k].values())) * us, 1)
              for k in cpu1 if k != "gateway"}
    out = {"rate": round(rate), "gateway_us": round(sum(threads.values()), 1),
           "threads_us": threads, "others_us": others,
           "segments_out": round((seg1["data_segs_out"] - seg0["data_segs_out"]) / publications, 3),
           "segments_in": round((seg1["data_segs_in"] - seg0["data_segs_in"]) / publications, 3)}
    if syscalls:
        out["syscalls"] = {f"{t} {c}": round(n / publications, 3)
                           for (t, c), n in sorted(syscalls.items()) if n}
    return out


def report(builds, rounds):
    med = statistics.median
    for label, _ in builds:
        runs = [r[label] for r in rounds]
        print(f"{label}: {med(r['rate'] for r in runs):,.0f} publications/s, gateway "
              f"{med(r['gateway_us'] for r in runs):.1f} us/publication, segments out "
              f"{med(r['segments_out'] for r in runs):.2f} / in "
              f"{med(r['segments_in'] for r in runs):.2f} per publication (medians)")
    first = builds[0][0]
    for label, _ in builds[1:]:
        rates = [r[first]["rate"] / r[label]["rate"] for r in rounds if r[label]["rate"]]
        cpu = [r[first]["gateway_us"] / r[label]["gateway_us"] for r in rounds
               if r[label]["gateway_us"]]
        print(f"{first} / {label}: rate {med(rates):.2f} (rounds "
              f"{', '.join(f'{x:.2f}' for x in rates)}), gateway CPU/publication {med(cpu):.2f}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("builds", nargs="+", metavar="LABEL=BINARY")
    parser.add_argument("--rounds", type=int, default=4)
    parser.add_argument("--rate", type=int, default=6000, help="datagrams/s")
    parser.add_argument("--seconds", type=float, default=8.0, help="of load per run")
    parser.add_argument("--syscalls", action="store_true")
    parser.add_argument("--tuned", action="store_true",
                        help="the bench's tuned broker (1,000 in flight, 65,535 topic aliases)")
    parser.add_argument("--mqtt", action="append", default=[], metavar="LABEL=LINE",
                        help="a line added to that build's mqtt section, e.g. "
                             "'off=describe_payloads: false' (repeatable)")
    args = parser.parse_args()
    args.mqtt_extra = {}
    for item in args.mqtt:
        label, line = item.split("=", 1)
        args.mqtt_extra.setdefault(label, []).append(line)
    builds = [tuple(b.split("=", 1)) for b in args.builds]
    tmp = tempfile.mkdtemp(prefix="eip2mqtt-probe-")
    broker_port = free_port()
    command = ["mosquitto", "-p", str(broker_port)]
    if args.tuned:
        conf = os.path.join(tmp, "tuned.conf")
        with open(conf, "w") as f:
            f.write(tuned_broker_config(broker_port))
        command = ["mosquitto", "-c", conf]
    broker = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rounds = []
    try:
        wait_for(lambda: listening(broker_port), 10, "the broker")
        for r in range(args.rounds):
            results = {}
            for label, binary in (builds if r % 2 == 0 else builds[::-1]):
                results[label] = one_run(args, tmp, broker, broker_port, f"p{r}{label}", label,
                                         binary)
                print(json.dumps({"round": r + 1, "build": label, **results[label]}), flush=True)
            rounds.append(results)
    finally:
        broker.terminate()
        broker.wait(5)
    report(builds, rounds)


if __name__ == "__main__":
    main()
