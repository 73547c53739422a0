"""The gateway configurations the scenarios run: one YAML file (and, with point lists, one CSV)
per gateway, in the run's temporary directory. Only the keys a scenario needs are written, the
defaults left out, so that an earlier build (--against-binary), whose configuration lacks some
of today's keys, reads every configuration that does not need them."""

import os

from benchlib.util import HOST

# `eip.link_mbps` for loopback (the most the key takes): 1,000 produced exchanges at 10 ms
# would be refused on the default 100 Mbit/s link.
LOOPBACK_MBPS = 400000


# What every consumed tag carries with `scaled`: a linear scale with its range's limit check,
# the costliest path of a publication (engineering values, docs/configuration.md).
SCALE = ", scale: { raw: [0, 1000000], eu: [0, 100] }"


def tag_lines(tags, writable, scaled=False):
    """Tag 0 is the lint "ts", tags 1.. dints (load_generator's layout)."""
    w = (", writable: true" if writable else "") + (SCALE if scaled else "")
    out = [f'      - {{ name: ts, address: "0.0", type: lint{w} }}']
    for t in range(1, tags):
        out.append(f'      - {{ name: t{t}, address: "{8 + 4 * (t - 1)}.0", type: dint{w} }}')
    return out


def flow_map(keys):
    """{key: YAML text} as a YAML flow mapping."""
    return "{ " + ", ".join(f"{k}: {v}" for k, v in keys.items()) + " }"


def head_lines(name, state, broker_port, qos, batch, udp_port, sparkplug, prometheus,
               store_and_forward, log_level, commands=None, link_mbps=None, redundancy=None,
               location=None, mqtt_keys=None):
    """Everything above `exchanges:`."""
    where = f", location: {flow_map(location)}" if location else ""
    mqtt_keys = mqtt_keys or {}
    url = [] if "url" in mqtt_keys else [f"  url: tcp://{HOST}:{broker_port}"]
    lines = [
        f"gateway: {{ id: {name}, state_dir: {state}, log_level: {log_level}{where} }}",
        "mqtt:",
    ] + url + [
        "  base_topic: b",
        f"  qos: {qos}",
        "  retain: false",
        "  metrics_interval_s: 1",
        "  buffer: { max_messages: 250000 }",  # above any scenario's topic count
    ]
    lines += [f"  {key}: {value}" for key, value in mqtt_keys.items()]
    if batch:
        lines.append("  batch: true")
    if batch == "first":
        lines.append("  batch_first: true")
    if store_and_forward:
        lines.append(f"  store_and_forward: {flow_map(store_and_forward)}")
    eip = f"bind: {HOST}, port: {udp_port}"
    if link_mbps:
        eip += f", link_mbps: {link_mbps}"
    if commands:  # the command responder's keys, as {key: YAML text}
        eip += f", commands: {flow_map(commands)}"
    lines.append(f"eip: {{ {eip} }}")
    if prometheus:
        lines.append(f"metrics: {{ listen: {HOST}:{prometheus} }}")
    if sparkplug:
        # Sparkplug alone (uns: false); its births and data are QoS 0, the specification's.
        lines.append("sparkplug: { group_id: bench, uns: false }")
    if redundancy:
        lines.append(f"redundancy: {flow_map(redundancy)}")
    return lines


def consumed_lines(name, consumed, point_list, scaled=False):
    """The consumed exchanges' YAML, and the point list's CSV rows (with point_list)."""
    lines = []
    rows = ["TagName,Node,Address,DataType,AccessType"]
    for exchange_id, tags in consumed:
        lines += [
            f"  - name: e{exchange_id}",
            "    direction: consume",
            "    producer_id: 10.0.0.1",
            f"    exchange_id: {exchange_id}",
            f"    length: {8 + 4 * (tags - 1)}",
            "    period_ms: 1000",
            "    timeout_ms: 0",
            f"    topic: e{exchange_id}",
        ]
        if point_list:
            lines.append(f"    points: {name}.csv")
            rows.append(f"ts,e{exchange_id},0.0,Long,Read")
            rows += [f"t{t},e{exchange_id},{8 + 4 * (t - 1)}.0,DInt,Read" for t in range(1, tags)]
        else:
            lines += ["    tags:"] + tag_lines(tags, False, scaled)
    return lines, rows


def produced_lines(produced):
    lines = []
    for exchange_id, tags, period, destination in produced:
        lines += [
            f"  - name: p{exchange_id}",
            "    direction: produce",
            "    producer_id: 10.0.0.2",
            f"    exchange_id: {exchange_id}",
            f"    destination: {destination}",
            f"    period_ms: {period}",
            f"    topic: p{exchange_id}",
            "    tags:",
        ] + tag_lines(tags, True)
    return lines


def write_config(tmp, name, broker_port, consumed=(), produced=(), qos=1, batch=False,
                 udp_port=0, point_list=False, sparkplug=False, prometheus=0,
                 store_and_forward=None, log_level="warn", state_suffix="", commands=None,
                 link_mbps=None, redundancy=None, scaled=False, location=None, mqtt_keys=None):
    """consumed: list of (exchange_id, tags); produced: list of (exchange_id, tags, period_ms,
    destination). With point_list, the consumed tags are rows of one CSV ({name}.csv, a SCADA
    point list whose Node column names the exchange) that every consumed exchange names in
    `points:`. batch: True for `_values`, "first" for `_values` first (batch_first).
    state_suffix: the state directory's, so that each build keeps its own. commands: the
    `eip.commands` keys ({key: YAML text}), for the command responder. link_mbps: the
    `eip.link_mbps` to write (None: none). redundancy: the `redundancy` keys ({key: YAML
    text}), for a unit of a hot-standby pair. scaled: every consumed tag written inline gets
    SCALE. location: the gateway's `location` ({key: YAML text}); mqtt_keys: more `mqtt` keys
    ({key: YAML text}), `url` among them instead of `broker_port`'s."""
    path = os.path.join(tmp, name + ".yaml")
    state = os.path.join(tmp, name + "-state" + state_suffix)
    os.makedirs(state, exist_ok=True)
    lines = head_lines(name, state, broker_port, qos, batch, udp_port, sparkplug, prometheus,
                       store_and_forward, log_level, commands, link_mbps, redundancy,
                       location, mqtt_keys)
    lines.append("exchanges:")
    consumed_yaml, rows = consumed_lines(name, consumed, point_list, scaled)
    lines += consumed_yaml + produced_lines(produced)
    if point_list:
        with open(os.path.join(tmp, name + ".csv"), "w") as f:
            f.write("\n".join(rows) + "\n")
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")
    return path
