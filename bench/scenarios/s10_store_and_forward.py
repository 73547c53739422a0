"""Scenario 10: store and forward. What journaling costs the zero-loss datagram rate, how fast
a journal replays, and its disk bytes per tag update."""

import os
import socket
import subprocess
import time

from benchlib.util import TAGS, consumed_list, free_port, stop

EXCHANGES, CHANGE = 100, 0.1
PER_DATAGRAM = round(CHANGE * TAGS)  # "ts" and the next dints (load_generator)
ACCEPTED = "eip2mqtt_datagrams_accepted_total"


def ceiling_config(bench, name, saf, build, udp_port=0, prom=0):
    return bench.write_config(name, consumed=consumed_list(100), qos=1, batch=True,
                              udp_port=udp_port, broker_port=free_port(), prometheus=prom,
                              store_and_forward=saf, build=build)


def ceiling(bench, name, saf, duration, steps, build):
    """Zero-loss datagram rate, 100 x 100 tags, 10 % changing, batch mode, the broker out of
    reach (a port nobody listens on): journaled, or buffered in memory."""
    udp_port, prom = free_port(socket.SOCK_DGRAM), free_port()
    config = ceiling_config(bench, name, saf, build, udp_port, prom)
    gw = bench.start_gateway(name, config, build=build)
    # The quick form starts from the gateway's first page with the count (its socket is bound
    # by then), and takes a trial's settled page as the next one's start (nothing is sent
    # between them), rather than settle them.
    first = bench.quick and (bench.prometheus_until(prom, lambda page: ACCEPTED in page) or {})
    state = {"id": 0, "settled": first}

    def trial(rate, n):
        before = state["settled"] if bench.quick else bench.settled_prometheus(prom, ACCEPTED)
        gen = bench.generate(udp_port, EXCHANGES, rate, duration=duration, change=CHANGE,
                             extra=["--request-id", str(state["id"])])
        state["id"] = (state["id"] + -(-gen["sent"] // EXCHANGES) + 1) % 65536
        after = state["settled"] = bench.settled_prometheus(prom, ACCEPTED)
        accepted = after.get(ACCEPTED, 0) - before.get(ACCEPTED, 0)
        ok = accepted == gen["sent"] and gen["errors"] == 0
        print(f"    {name} {rate:9.0f}/s: sent {gen['sent']} accepted {accepted:.0f} "
              f"({gen['rate']:.0f}/s)", flush=True)
        return ok, gen["rate"]

    rate, _ = bench.zero_loss_ceiling(trial, steps, 10000, "scenario 10")
    stop(gw)
    return rate


def replayed_from_log(log):
    """(entries, seconds) from "store and forward: N journaled entries replayed in X s" (the
    gateway's own clock), or (0, None) while the line is not there."""
    with open(log) as f:
        for line in f:
            if "journaled entries replayed in" in line:
                return (int(line.split("store and forward: ")[1].split()[0]),
                        float(line.split(" replayed in ")[1].split()[0]))
    return 0, None


def replay(bench, journaled, build):
    """A known outage journaled by `build`, then replayed as fast as the broker takes it."""
    count = 10000 if bench.quick else 200000
    name, udp_port, prom, port = "g10r", free_port(socket.SOCK_DGRAM), free_port(), free_port()
    config = bench.write_config(name, consumed=consumed_list(100), qos=1, batch=True,
                                udp_port=udp_port, broker_port=port, prometheus=prom,
                                log_level="info",
                                store_and_forward={"enabled": "true", "replay_rate": 1000000},
                                build=build)
    gw = bench.start_gateway(name, config, build=build)
    time.sleep(0.5)
    gen = bench.generate(udp_port, EXCHANGES, min(20000, journaled or 20000), count=count,
                         change=CHANGE)
    # The quick form reads on once every datagram sent is journaled, unless one was lost.
    page = bench.quick and bench.prometheus_until(
        prom, lambda p: p.get("eip2mqtt_history_entries", 0) >= gen["sent"], timeout=5)
    page = page or bench.settled_prometheus(prom, "eip2mqtt_history_entries")
    broker = subprocess.Popen(["mosquitto", "-p", str(port)], stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL)
    bench.procs.append(broker)
    replayed, replay_s = 0, None
    deadline = time.monotonic() + 120
    while replay_s is None and time.monotonic() < deadline:
        time.sleep(0.2)
        replayed, replay_s = replayed_from_log(os.path.join(bench.tmp, name + ".log"))
    stop(gw)
    stop(broker)
    return {"sent": gen["sent"], "entries": page.get("eip2mqtt_history_entries", 0),
            "disk": page.get("eip2mqtt_history_bytes", 0), "replayed": replayed,
            "replay_s": replay_s}


def replay_rows(bench, runs):
    r = runs[bench.build]["replay"]
    entries, disk, replayed = r["entries"], r["disk"], r["replayed"]
    rate = replay_rate(r)
    bench.row("history replay rate, messages/s (_history, QoS 1, Debian's default Mosquitto)",
              f"{rate:,.0f} ({rate * PER_DATAGRAM:,.0f} tag updates/s)",
              f"{entries:,.0f} entries journaled", "-", ">= 2,000 (default replay_rate)",
              "yes" if rate >= 2000 and replayed == entries else "no",
              bench.versus([runs], lambda o: replay_rate(o["replay"])))
    updates = journaled_updates(r)
    bench.row("journal disk bytes per journaled tag update (file + WAL)",
              f"{disk_per_update(r):.1f}",
              f"{updates:,.0f} tag updates in {disk / 1e6:.1f} MB", "-", "-", "-",
              bench.versus([runs], lambda o: disk_per_update(o["replay"]), fmt="{:.1f}".format))


def replay_rate(r):
    return r["replayed"] / r["replay_s"] if r["replay_s"] else 0


def journaled_updates(r):
    """Every tag of an exchange's first datagram, then PER_DATAGRAM of each next one."""
    return r["entries"] * PER_DATAGRAM + EXCHANGES * (TAGS - PER_DATAGRAM)


def disk_per_update(r):
    updates = journaled_updates(r)
    return r["disk"] / updates if updates else 0


def measure(bench, build):
    """Every figure of the scenario on `build`; NotInBuild at once when it has no store and
    forward."""
    build.require(ceiling_config(bench, "g10probe", {"enabled": "true"}, build))
    duration = 1 if bench.quick else 2
    steps = 1 if bench.quick else 3
    memory = ceiling(bench, "g10m", None, duration, steps, build)
    journaled = ceiling(bench, "g10j", {"enabled": "true"}, duration, steps, build)
    r = replay(bench, journaled, build)
    print(f"    {build.label}: sent {r['sent']} datagrams; journaled {r['entries']:.0f} entries, "
          f"{r['disk']:.0f} bytes; replayed {r['replayed']:.0f} in {r['replay_s']} s", flush=True)
    return {"memory": memory, "journaled": journaled, "replay": r}


def run(bench):
    print("[10] store and forward: journaling cost, replay rate, disk per tag update",
          flush=True)
    runs = bench.per_build(0, lambda build: measure(bench, build))
    memory, journaled = runs[bench.build]["memory"], runs[bench.build]["journaled"]
    ratio = journaled / memory if memory else 0
    bench.row(f"datagrams/s accepted, zero loss, journaling ({EXCHANGES} x {TAGS} tags, "
              f"10 % changing, broker down)", f"{journaled:,.0f}",
              f"{memory:,.0f} (same, without store and forward)", f"{ratio:.2f}", ">= 0.90",
              "yes" if ratio >= 0.9 else "no",
              bench.versus([runs], lambda o: o["journaled"]))
    replay_rows(bench, runs)
