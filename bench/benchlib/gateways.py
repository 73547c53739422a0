"""The gateway under test: its configuration, its start, and what it says about itself (its
state and metrics topics, its Prometheus page)."""

import json
import os
import socket
import subprocess
import time

from benchlib import config
from benchlib.util import HOST, free_port


class Gateways:
    def write_config(self, name, broker_port=None, build=None, **kwargs):
        """config.write_config in this run's directory, on the broker in use by default, with a
        state directory of `build`'s own (the build under test's by default)."""
        suffix = "" if build is None or build.new else "-against"
        # Loopback is no Ethernet link: a build that checks a schedule's load against
        # `eip.link_mbps` is told that the link is as fast as it allows.
        link = config.LOOPBACK_MBPS if (build or self.build).reads_eip_key(
            "link_mbps", config.LOOPBACK_MBPS) else None
        return config.write_config(self.tmp, name, broker_port or self.broker_port,
                                   state_suffix=suffix, link_mbps=link, **kwargs)

    def start_gateway(self, name, config_path, notify_socket=None, args=(), build=None):
        """`build` (the build under test by default) running `config_path`; NotInBuild when an
        earlier build refuses the configuration."""
        build = build or self.build
        build.require(config_path)
        log = open(os.path.join(self.tmp, name + ".log"), "w")
        env = dict(os.environ)
        env.pop("NOTIFY_SOCKET", None)
        if notify_socket:
            env["NOTIFY_SOCKET"] = notify_socket
        proc = subprocess.Popen([build.gateway, "run", "-c", config_path, *args], stdout=log,
                                stderr=log, env=env)
        self.procs.append(proc)
        return proc

    def wait_said(self, name, topic, payload, timeout=10, proc=None, build=None):
        """Until gateway `name` says `payload` on `topic`. A retained message of an earlier
        instance of the same gateway may come first: read on (bounded by -W) rather than take
        the first message. An earlier build's gateway `proc` that ended instead is NotInBuild."""
        sub = subprocess.Popen(["mosquitto_sub", "-h", HOST, "-p", str(self.broker_port), "-W",
                                str(timeout), "-t", topic],
                               stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        seen = []
        try:
            for line in sub.stdout:
                seen.append(line.strip())
                if seen[-1] == payload:
                    return
        finally:
            sub.kill()
            sub.wait(timeout=5)
        if proc is not None:
            (build or self.build).start_failed(proc, os.path.join(self.tmp, name + ".log"))
        raise RuntimeError(f"gateway {name} did not say {payload} on {topic}: {seen!r}")

    def wait_online(self, name, timeout=10, proc=None, build=None):
        """Until the gateway's state topic says `online` (an `offline` retained by an earlier
        instance is read past)."""
        self.wait_said(name, f"b/_gateway/{name}/state", "online", timeout, proc, build)

    def wait_leading(self, name, timeout, proc=None, build=None):
        """Until the gateway, a unit of a hot-standby pair, says `leader` on its role topic
        (docs/redundancy.md): a lone unit leads once its takeover time passed unheard."""
        self.wait_said(name, f"b/_gateway/{name}/role", "leader", timeout, proc, build)

    def launch_gateway(self, name, consumed, qos, build=None, **config_args):
        """A gateway of `build` consuming `consumed` ((exchange, tags) pairs) on a UDP port of
        its own, started and online: (process, port)."""
        udp_port = free_port(socket.SOCK_DGRAM)
        path = self.write_config(name, consumed=consumed, qos=qos, udp_port=udp_port,
                                 build=build, **config_args)
        gw = self.start_gateway(name, path, build=build)
        self.wait_online(name, proc=gw, build=build)
        return gw, udp_port

    def metrics(self, name, timeout=4):
        """The next metrics publication of gateway `name` (every second)."""
        out = subprocess.run(["mosquitto_sub", "-h", HOST, "-p", str(self.broker_port), "-C", "1",
                              "-W", str(timeout), "-t", f"b/_gateway/{name}/metrics"],
                             capture_output=True, text=True, timeout=timeout + 5)
        return json.loads(out.stdout) if out.stdout.strip() else None

    def metrics_until(self, name, done, reads=10):
        """The first metrics publication of gateway `name` for which `done(metrics)` holds
        (bounded reads), or None."""
        for _ in range(reads):
            m = self.metrics(name)
            if m is not None and done(m):
                return m
        return None

    def settled_metrics(self, name, key="accepted", reads=6):
        """Metrics once `key` stopped moving between two publications (bounded reads)."""
        previous = None
        for _ in range(reads):
            m = self.metrics(name)
            if m is None:
                return previous
            if previous is not None and m[key] == previous[key] and m.get("buffered", 0) == 0:
                return m
            previous = m
        return previous

    def prometheus(self, port, timeout=2):
        """The gateway's Prometheus page as {name: value} (unlabelled figures only)."""
        import urllib.request
        try:
            with urllib.request.urlopen(f"http://{HOST}:{port}/metrics", timeout=timeout) as r:
                text = r.read().decode()
        except OSError:
            return {}
        out = {}
        for line in text.splitlines():
            if line and not line.startswith("#") and "{" not in line:
                name, _, value = line.partition(" ")
                out[name] = float(value)
        return out

    def prometheus_until(self, port, done, timeout=10):
        """The gateway's first Prometheus page for which `done(page)` holds (read every 0.05 s;
        the gateway refreshes it once a second), or None after `timeout`."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            page = self.prometheus(port)
            if done(page):
                return page
            time.sleep(0.05)
        return None

    def settled_prometheus(self, port, key, reads=10):
        """The page once `key` stopped moving between two refreshes (once a second; bounded)."""
        previous = None
        for _ in range(reads):
            time.sleep(1.1)
            page = self.prometheus(port)
            if previous and key in page and page[key] == previous.get(key):
                return page
            previous = page
        return previous or {}
