"""Scenario 18's fleet: N gateways, each in a network namespace of its own (benchlib.netns) with
its own simulated PLCs (the load generator, run in that namespace), publishing into an ejabberd
cluster (benchlib.ejabberd_cluster) in the segment's hub namespace, with an mqtt_counter on every
node. One FleetRun is one run of one build with N gateways; every process it starts is stopped
by `close`, and every wait is bounded."""

import json
import os
import subprocess
import time

from benchlib.cpu import CpuSampler
from benchlib.ejabberd_cluster import LOGIN
from benchlib.util import last_json, stop, tool, wait_file

EIP_PORT = 18246  # the protocol's own: each gateway has a namespace, and so a port, of its own
SKIP_MS = 500  # latency samples of the load's first moments left out, as in scenario 5
CONNECT_S = 60
# What ejabberd logs when it closes a session whose queue of messages to send went over
# mod_mqtt's `max_queue` (5,000 by default): a subscriber that falls behind is disconnected,
# whatever the QoS, and what was queued for it is lost.
OVERLOADED = "Message queue is overloaded"


class Plant:
    """What each gateway's PLCs send: `exchanges` exchanges of `tags` tags (`ts`, a lint, then
    dints) every `period_ms`, `change` of the tags changing in each datagram; published at
    `qos`."""

    def __init__(self, exchanges, tags, period_ms, change, qos):
        self.exchanges, self.tags, self.period_ms = exchanges, tags, period_ms
        self.change, self.qos = change, qos
        self.datagrams = exchanges * 1000 // period_ms  # per second
        self.changed = max(1, round(change * tags))  # tags per datagram

    def expected(self, sent):
        """Tag updates a gateway publishes for `sent` datagrams after its warm-up: the changed
        tags of each."""
        return sent * self.changed


def read_dump(path):
    """The latency samples (us) of a counter's --dump file."""
    try:
        with open(path) as f:
            return [float(line.split()[1]) for line in f if line.strip()]
    except OSError:
        return []


class FleetRun:
    """`count` gateways of `build` in the first `count` of `members` (namespaces on `segment`),
    a subscriber per node of `cluster`, and `duration` s of `plant`'s load."""

    def __init__(self, bench, segment, members, cluster, build, count, duration, plant):
        self.bench, self.segment, self.cluster = bench, segment, cluster
        self.members, self.build = members[:count], build
        self.count, self.duration, self.plant = count, duration, plant
        self.procs = []
        self.tag = f"f18n{count}" + ("" if build.new else "x")

    def spawn(self, argv, **kwargs):
        proc = subprocess.Popen(argv, **kwargs)
        self.procs.append(proc)
        self.bench.procs.append(proc)
        return proc

    def close(self):
        for proc in self.procs:
            stop(proc)

    def start_subscriber(self, j):
        """mqtt_counter on node j, subscribed: (process, its latency dump's path)."""
        node = self.cluster.nodes[j]
        ready = os.path.join(self.bench.tmp, f"{self.tag}-sub{j}.ready")
        dump = os.path.join(self.bench.tmp, f"{self.tag}-sub{j}.latency")
        argv = [tool("mqtt_counter"), "--host", "127.0.0.1", "--port", node.port,
                "--filter", "b/+/+", "--qos", self.plant.qos, "--max-s", self.duration + 120,
                "--idle-ms", 1500 if self.bench.quick else 3000, "--ready-file", ready,
                "--id", f"bench-fleet-{self.tag}-{j}", "--skip-ms", SKIP_MS, "--dump", dump,
                "--username", LOGIN[0], "--password", LOGIN[1]]
        proc = self.spawn(self.segment.hub.inside(argv), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
        if not wait_file(ready, 15):
            raise RuntimeError(f"mqtt_counter on {node.name} did not subscribe")
        return proc, dump

    def urls(self, i):
        """The cluster's nodes from node i % 3 on, as `mqtt.url`: the fleet spreads."""
        nodes = self.cluster.nodes
        order = [nodes[(i + k) % len(nodes)] for k in range(len(nodes))]
        return "[ " + ", ".join(f"tcp://{self.segment.hub_address}:{n.port}" for n in order) + " ]"

    def start_gateway(self, i):
        """Gateway i in its namespace, exchanges 1 + i x exchanges on: (name, process, log)."""
        name = f"{self.tag}g{i}"
        first = 1 + i * self.plant.exchanges
        path = self.bench.write_config(
            name, consumed=[(first + e, self.plant.tags) for e in range(self.plant.exchanges)],
            qos=self.plant.qos, udp_port=EIP_PORT, build=self.build, log_level="info",
            mqtt_keys={"url": self.urls(i), "username": LOGIN[0]})
        self.build.require(path)
        log_path = os.path.join(self.bench.tmp, name + ".log")
        env = {k: v for k, v in os.environ.items() if k != "NOTIFY_SOCKET"}
        env["EIP2MQTT_MQTT_PASSWORD"] = LOGIN[1]
        with open(log_path, "w") as log:
            proc = self.spawn(self.members[i].inside([self.build.gateway, "run", "-c", path]),
                              stdout=log, stderr=log, env=env)
        return name, proc, log_path

    def wait_connected(self, gateways):
        """Until every gateway logged `MQTT connected to` (CONNECT_S at most)."""
        deadline = time.monotonic() + CONNECT_S
        waiting = list(gateways)
        while waiting and time.monotonic() < deadline:
            for gw in list(waiting):
                name, proc, log_path = gw
                with open(log_path, errors="replace") as f:
                    if "MQTT connected to" in f.read():
                        waiting.remove(gw)
                        continue
                if proc.poll() is not None:
                    self.build.start_failed(proc, log_path)
                    raise RuntimeError(f"gateway {name} ended ({proc.returncode})")
            time.sleep(0.05)
        for name, proc, log_path in waiting:
            self.build.start_failed(proc, log_path)
            raise RuntimeError(f"gateway {name} did not connect within {CONNECT_S} s")

    def load(self, gateways, subscribers):
        """Every gateway's generator at once, the CPU of every process sampled: (datagrams
        sent per gateway, CpuSampler.per_publication by process, tag updates/s offered)."""
        plant, generators = self.plant, []
        for i in range(self.count):
            argv = self.bench.generator_args(EIP_PORT, plant.exchanges, plant.datagrams,
                                             self.duration, change=plant.change,
                                             tags=plant.tags, first=1 + i * plant.exchanges,
                                             extra=["--request-id", "1"])  # after the warm-up's
            generators.append(self.spawn(self.members[i].inside(argv), stdout=subprocess.PIPE,
                                         stderr=subprocess.PIPE, text=True))
        groups = {f"gw{i}": [proc.pid] for i, (_, proc, _) in enumerate(gateways)}
        groups.update({f"gen{i}": [g.pid] for i, g in enumerate(generators)})
        groups.update({f"node{j}": [vm] for j, vm in enumerate(self.cluster.vm_pids())})
        groups.update({f"sub{j}": [s.pid] for j, (s, _) in enumerate(subscribers)})
        sampler = CpuSampler(groups, min(0.25, self.duration / 10)).start()
        sent = []
        try:
            for g in generators:
                out, err = g.communicate(timeout=self.duration + 60)
                if g.returncode != 0:
                    raise RuntimeError(f"load_generator failed ({g.returncode}): {err[-300:]}")
                sent.append(last_json(out)["sent"])
        finally:
            sampler.stop()
        offered = sum(plant.expected(s) for s in sent) / self.duration
        return sent, sampler.per_publication(offered, self.duration), offered

    def warm_up(self, gateways):
        """One datagram per exchange, nothing changing (every tag 0), to each gateway: the
        first value of every tag, a one-off burst of exchanges x tags publications (more than
        the gateway's window in flight: the next datagrams' values would replace some of them
        while they wait, and count as lost), published before the subscribers subscribe, as in
        scenario 5. Returns once every gateway says all of them were acknowledged."""
        plant = self.plant
        for i in range(self.count):
            argv = self.bench.generator_args(EIP_PORT, plant.exchanges, 1000,
                                             count=plant.exchanges, change=0, tags=plant.tags,
                                             first=1 + i * plant.exchanges)
            out = subprocess.run(self.members[i].inside(argv), capture_output=True, text=True,
                                 timeout=60)
            if out.returncode != 0:
                raise RuntimeError(f"load_generator failed ({out.returncode}): {out.stderr}")
        names = {name for name, _, _ in gateways}
        first_values = plant.exchanges * plant.tags
        # (An earlier build without a key is taken at its word.)
        seen = self.watch_metrics(names, lambda m: m.get("published", first_values) >=
                                  first_values and m.get("buffered", 0) == 0, 30)
        if names - set(seen):
            raise RuntimeError(f"gateways {sorted(names - set(seen))} did not publish every "
                               f"tag's first value within 30 s: {seen}")

    def watch_metrics(self, names, done, timeout):
        """{gateway name: its latest metrics} heard on node 0 (QoS 0, every second) until
        `done(metrics)` held for every gateway of `names`, or `timeout` s passed."""
        node = self.cluster.nodes[0]
        sub = subprocess.Popen(self.segment.hub.inside(
            ["mosquitto_sub", "-h", "127.0.0.1", "-p", node.port, "-u", LOGIN[0], "-P", LOGIN[1],
             "-t", "b/_gateway/+/metrics", "-F", "%t %p", "-W", timeout]),
            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        seen, ready = {}, set()
        try:
            for line in sub.stdout:  # ends with mosquitto_sub, at -W at the latest
                topic, _, payload = line.partition(" ")
                try:
                    name, metrics = topic.split("/")[2], json.loads(payload)
                except (ValueError, IndexError):
                    continue
                seen[name] = metrics
                if done(metrics):
                    ready.add(name)
                if ready >= names:
                    break
        finally:
            stop(sub, timeout=5)
        return {name: seen[name] for name in ready}

    def gateway_metrics(self):
        """{gateway name: its metrics} once every gateway has nothing left to send (20 s at
        most; a gateway still sending then is left out)."""
        names = {f"{self.tag}g{i}" for i in range(self.count)}
        return self.watch_metrics(names, lambda m: m.get("buffered", 0) == 0, 20)

    def measure(self):
        """The run: {"sent": datagrams per gateway, "cpu", "offered": updates/s, "got": [(each
        subscriber's count, its latency samples)], "metrics": by gateway, "closed": subscriber
        sessions ejabberd closed, overloaded}."""
        gateways = [self.start_gateway(i) for i in range(self.count)]
        self.wait_connected(gateways)
        self.warm_up(gateways)
        subscribers = [self.start_subscriber(j) for j in range(len(self.cluster.nodes))]
        closed = self.cluster.logged(OVERLOADED)
        started = time.monotonic()
        sent, cpu, offered = self.load(gateways, subscribers)
        load_s = time.monotonic() - started
        got = []
        for proc, dump in subscribers:
            out, _ = proc.communicate(timeout=self.duration + 150)
            counted = last_json(out)
            counted["lag_s"] = max(0.0, counted["first_to_last_s"] - load_s)
            # Over the load's time, or over the deliveries' when they outlasted it.
            counted["rate"] = counted["updates"] / max(counted["first_to_last_s"], self.duration)
            got.append((counted, read_dump(dump)))
        closed = [after - before for after, before in zip(self.cluster.logged(OVERLOADED), closed)]
        return {"sent": sent, "cpu": cpu, "offered": offered, "got": got,
                "metrics": self.gateway_metrics(), "closed": sum(closed)}
