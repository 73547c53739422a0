"""The processes a run starts besides the gateway: its two brokers, the subscriber that counts
(mqtt_counter), the bare UDP receiver (udp_sink) and the load generator. Every process started
is registered, and stopped by `close`."""

import os
import shutil
import subprocess
import socket
import time

from benchlib.util import HOST, TAGS, last_json, run_json, stop, tool, wait_file, free_port


def tuned_broker_config(port):
    """mosquitto.conf of the tuned broker, listening on `port` of the loopback."""
    return (
        f"listener {port} {HOST}\n"
        "allow_anonymous true\n"
        "persistence false\n"
        "log_dest none\n"
        "set_tcp_nodelay true\n"
        "max_inflight_messages 1000\n"
        "max_queued_messages 1000000\n"
        "max_queued_bytes 0\n"
        "max_topic_alias 65535\n"  # every topic's alias (scenario 15)
    )


class Processes:
    def start_broker(self):
        """Starts both brokers; the tuned one is used unless a scenario says otherwise."""
        port = free_port()
        conf = os.path.join(self.tmp, "mosquitto.conf")
        with open(conf, "w") as f:
            f.write(tuned_broker_config(port))
        self.spawn_broker("tuned", ["mosquitto", "-c", conf], port)
        # No configuration file: Mosquitto 2.0's defaults, listening on the loopback only.
        port = free_port()
        self.spawn_broker("default", ["mosquitto", "-p", str(port)], port)
        self.use_broker("tuned")

    def spawn_broker(self, setup, args, port):
        proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.brokers[setup] = (proc, port)
        deadline = time.monotonic() + 5
        while time.monotonic() < deadline:
            try:
                socket.create_connection((HOST, port), timeout=0.2).close()
                return
            except OSError:
                time.sleep(0.05)
        raise RuntimeError(f"mosquitto ({setup}) did not start")

    def use_broker(self, setup):
        self.broker_port = self.brokers[setup][1]

    def close(self):
        for p in self.procs:
            stop(p)
        for proc, _ in self.brokers.values():
            stop(proc)
        if os.environ.get("EIP2MQTT_BENCH_KEEP"):
            print(f"kept {self.tmp}")
        else:
            shutil.rmtree(self.tmp, ignore_errors=True)

    def start_counter(self, filters, qos, extra=(), max_s=120, idle_ms=None):
        """mqtt_counter on `filters`, subscribed; it ends `idle_ms` (the run's by default)
        after the last message."""
        idle_ms = idle_ms or self.idle_ms
        self.counter_seq += 1
        ready = os.path.join(self.tmp, f"counter{self.counter_seq}.ready")
        args = [tool("mqtt_counter"), "--port", str(self.broker_port), "--filter", filters,
                "--qos", str(qos), "--max-s", str(max_s), "--idle-ms", str(idle_ms),
                "--ready-file", ready, "--id", f"bench-counter-{self.counter_seq}"] + list(extra)
        proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.procs.append(proc)
        if not wait_file(ready, 5):
            raise RuntimeError("mqtt_counter did not subscribe")
        return proc

    def start_sink(self, port, *args, stdout=subprocess.PIPE):
        """A bare recvmmsg receiver (bench/udp_sink) on `port`, once it has bound."""
        self.counter_seq += 1
        ready = os.path.join(self.tmp, f"sink{self.counter_seq}.ready")
        proc = subprocess.Popen([tool("udp_sink"), "--port", str(port), *map(str, args),
                                 "--ready-file", ready], stdout=stdout, text=True)
        self.procs.append(proc)
        if not wait_file(ready, 5):
            raise RuntimeError("udp_sink did not bind")
        return proc

    def finish(self, proc, timeout=150):
        out, err = proc.communicate(timeout=timeout)
        return last_json(out)

    @staticmethod
    def generator_args(port, exchanges, rate, duration=None, count=None, change=0.1,
                       stamp=True, tags=TAGS, first=1, extra=()):
        args = [tool("load_generator"), "--port", str(port), "--exchanges", str(exchanges),
                "--first-exchange", str(first), "--tags", str(tags), "--rate", str(rate),
                "--change", str(change)]
        args += ["--count", str(count)] if count is not None else ["--duration", str(duration)]
        if not stamp:
            args.append("--no-stamp")
        return args + list(extra)

    def generate(self, port, exchanges, rate, duration=None, **kwargs):
        """Runs the load generator to its end; its JSON line."""
        return run_json(self.generator_args(port, exchanges, rate, duration, **kwargs),
                        timeout=(duration or 10) + 60)

    def start_generator(self, port, exchanges, rate, duration, **kwargs):
        """The load generator, started and left running (registered for cleanup)."""
        proc = subprocess.Popen(self.generator_args(port, exchanges, rate, duration, **kwargs),
                                stdout=subprocess.PIPE, text=True)
        self.procs.append(proc)
        return proc
