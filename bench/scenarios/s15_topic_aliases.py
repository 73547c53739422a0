"""Scenario 15: MQTT bytes on the wire per tag update (what a tap between the gateway and its
broker reads): on long unified-namespace topics (5 levels, 60 characters) with topic aliases
against without, on each broker (the tuned one takes every topic's alias, max_topic_alias 65535;
Debian's default Mosquitto takes 10); and what MQTT 5's metadata costs on today's topics."""

import socket
import time

from benchlib.mqtt_tap import MqttTap
from benchlib.util import TAGS, consumed_list, free_port, stop

# {enterprise}/{site}/{area}/{exchange}/{tag}: "acme-energy/riverside-power-station/
# turbine-hall-east/e1/t42" is 60 characters (the tags t1..t9 and ts, 59).
LOCATION = {"enterprise": "acme-energy", "site": "riverside-power-station",
            "area": "turbine-hall-east"}
PREFIX = "/".join(LOCATION.values()) + "/"
TEMPLATE = '"{enterprise}/{site}/{area}/{exchange}/{tag}"'
RATE = 20  # datagrams/s of 100 changing tags: 2,000 tag updates/s, far below any ceiling


def settle(tap, prefix, expected, quiet_s=2.0, limit_s=30.0):
    """Until the tap saw `expected` tag updates, or none more for `quiet_s` (bounded)."""
    deadline = time.monotonic() + limit_s
    seen, since = -1, time.monotonic()
    while time.monotonic() < deadline:
        count = sum(1 for topic, _, _ in tap.snapshot()[0] if topic.startswith(prefix))
        if count >= expected:
            return
        if count != seen:
            seen, since = count, time.monotonic()
        elif time.monotonic() - since > quiet_s:
            return
        time.sleep(0.2)


def measure(bench, name, mqtt_keys, laid_out=True, build=None):
    """`build`'s gateway between a tap and the broker in use, for one run of tag updates, with
    `mqtt_keys` on the UNS topics (`laid_out`) or today's: {"bytes": PUBLISH bytes per tag
    update, "aliased": the share sent by alias, "updates", "topic": the mean topic length}."""
    tap = MqttTap(bench.broker_port)
    prefix = PREFIX if laid_out else "b/e1/"
    keys = {"topic_template": TEMPLATE, **mqtt_keys} if laid_out else mqtt_keys
    try:
        udp_port = free_port(socket.SOCK_DGRAM)
        path = bench.write_config(
            name, broker_port=tap.port, consumed=consumed_list(1), udp_port=udp_port, build=build,
            location=LOCATION if laid_out else None, mqtt_keys=keys)
        gw = bench.start_gateway(name, path, build=build)
        bench.wait_online(name, proc=gw, build=build)
        before = len(tap.snapshot()[0])
        datagrams = max(2, round(RATE * bench.d * 2))
        bench.generate(udp_port, 1, RATE, count=datagrams, change=1.0)
        settle(tap, prefix, before + datagrams * TAGS)
        stop(gw)
        publications, duplicates = tap.snapshot()
    finally:
        tap.close()
    data = [p for p in publications[before:] if p[0].startswith(prefix)]
    if not data:
        raise RuntimeError(f"gateway {name}: no tag update reached the broker")
    return {"bytes": (sum(size for _, size, _ in data) + duplicates) / len(data),
            "aliased": sum(1 for *_, by_alias in data if by_alias) / len(data),
            "updates": len(data), "topic": sum(len(t) for t, _, _ in data) / len(data)}


def alias_row(bench, setup, label):
    print(f"[15] bytes per tag update, topic aliases, {label}", flush=True)
    bench.use_broker(setup)
    try:
        plain = measure(bench, "g15n", {"topic_aliases": "false"})
        runs = bench.per_build(0, lambda build: measure(bench, "g15a", {"topic_aliases": "true"},
                                                        build=build))
    finally:
        bench.use_broker("tuned")
    got = runs[bench.build]
    ratio = got["bytes"] / plain["bytes"]
    print(f"    {got['updates']} updates with aliases, {plain['updates']} without; topics of "
          f"{got['topic']:.1f} characters on average", flush=True)
    bench.row(f"MQTT bytes sent per tag update, topic aliases, 1 x {TAGS} tags on 5-level topics "
              f"of {got['topic']:.0f} characters, QoS 1, {label}",
              f"{got['bytes']:.1f} B ({got['aliased']:.1%} of updates by alias)",
              f"{plain['bytes']:.1f} B (aliases off, same run)", f"{ratio:.2f}", "< 1",
              "yes" if ratio < 1 else "no",
              bench.versus([runs], lambda g: g["bytes"], fmt="{:.1f} B".format))


def metadata_row(bench):
    """What the content type and format indicator every MQTT 5 message carries cost, against
    the same gateway over MQTT 3.1.1 (no properties) on today's topics; an earlier build runs
    the MQTT 5 configuration beside this one."""
    print("[15] bytes per tag update, MQTT 5 metadata, today's topics", flush=True)
    bare = measure(bench, "g15v", {"version": '"3.1.1"'}, laid_out=False)
    runs = bench.per_build(0, lambda build: measure(bench, "g15m", {}, False, build))
    got = runs[bench.build]
    bench.row(f"MQTT bytes sent per tag update, MQTT 5 (content type, format indicator), "
              f"1 x {TAGS} tags on today's topics ({got['topic']:.0f} characters), QoS 1, "
              "tuned broker", f"{got['bytes']:.1f} B",
              f"{bare['bytes']:.1f} B (MQTT 3.1.1, same run)",
              f"{got['bytes'] / bare['bytes']:.2f}", "-", "-",
              bench.versus([runs], lambda g: g["bytes"], fmt="{:.1f} B".format))


def run(bench):
    for setup, label in (("tuned", "tuned broker (max_topic_alias 65535)"),
                         ("default", "Debian's default broker (Topic Alias Maximum 10)")):
        alias_row(bench, setup, label)
    metadata_row(bench)
