"""Paths, constants and small helpers every part of the benchmark shares."""

import json
import os
import signal
import socket
import subprocess
import time

BENCH_DIR = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(BENCH_DIR)
BUILD = os.environ.get("EIP2MQTT_BENCH_BUILD", os.path.join(ROOT, "build-bench"))
GATEWAY = os.path.join(BUILD, "eip2mqtt")
# Where the table is written (the test of this driver writes into its build tree).
RESULTS = os.environ.get("EIP2MQTT_BENCH_RESULTS", os.path.join(BENCH_DIR, "results"))
TOOLS = os.path.join(BUILD, "bench")
HOST = "127.0.0.1"
FINAL_VALUE = 2000000007  # the overload run's last value of every tag
TAGS = 100
# Publications in flight for the bare Paho baseline: the gateway's own window (ClientOptions
# max_in_flight), so both pay the same for Paho C's per-publish list walks.
PAHO_WINDOW = 256
# The two brokers of scenarios 2, 3 and 5: ours, tuned for throughput, and Mosquitto as Debian
# installs it, with no configuration but a listener.
BROKERS = (("tuned", "tuned broker"), ("default", "Debian's default broker"))
# For experiments, e.g. EIP2MQTT_BENCH_SETUPS=default: the broker setups scenarios 2, 3 and 5 use.
SETUPS = [b for b in BROKERS
          if b[0] in os.environ.get("EIP2MQTT_BENCH_SETUPS", "tuned,default").split(",")]
# Exchange shapes of scenarios 2 and 3 (exchanges, tags): one large exchange, and many small
# ones, where per-exchange costs (each exchange's `_status`, say) show.
SHAPES = ((1, TAGS), (100, 10))


def tool(name):
    return os.path.join(TOOLS, name)


def free_port(kind=socket.SOCK_STREAM):
    with socket.socket(socket.AF_INET, kind) as s:
        s.bind((HOST, 0))
        return s.getsockname()[1]


def last_json(text):
    for line in reversed(text.strip().splitlines()):
        line = line.strip()
        if line.startswith("{"):
            return json.loads(line)
    raise RuntimeError("no JSON in output: " + text[-500:])


def run_json(args, timeout):
    out = subprocess.run(args, capture_output=True, text=True, timeout=timeout)
    if out.returncode != 0:
        raise RuntimeError(f"{args[0]} failed ({out.returncode}): {out.stderr[-500:]}")
    return last_json(out.stdout)


def wait_file(path, timeout):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if os.path.exists(path):
            return True
        time.sleep(0.01)
    return False


def rss_kb(pid, field="VmRSS"):
    try:
        with open(f"/proc/{pid}/status") as f:
            for line in f:
                if line.startswith(field + ":"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def rss_split_kb(pid):
    """Resident kB of a process by what holds it (/proc/PID/smaps): its own binary's pages,
    the main heap, other anonymous memory (threads' arenas and stacks, large blocks) and the
    shared libraries; the rest (locale files, the vDSO) is left out. Empty once the process is
    gone."""
    split = {"binary": 0, "heap": 0, "anonymous": 0, "libraries": 0}
    try:
        exe = os.readlink(f"/proc/{pid}/exe")
        with open(f"/proc/{pid}/smaps") as f:
            where = None
            for line in f:
                fields = line.split()
                if fields[0].endswith(":"):
                    if fields[0] == "Rss:" and where:
                        split[where] += int(fields[1])
                    continue
                path = fields[5] if len(fields) > 5 else ""
                where = ("binary" if path == exe else "heap" if path == "[heap]" else
                         "anonymous" if path in ("", "[stack]") else
                         "libraries" if ".so" in path else None)
    except OSError:
        return {}
    return split


def stop(proc, timeout=10):
    if proc is None or proc.poll() is not None:
        return
    proc.send_signal(signal.SIGTERM)
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait(timeout=5)


def median(values):
    return sorted(values)[len(values) // 2]


def consumed_list(count, tags=TAGS, first=1):
    """The consumed exchanges `first` .. `first + count - 1`, each of `tags` tags, as
    `write_config` takes them."""
    return [(i, tags) for i in range(first, first + count)]


def offered_datagrams(ceiling, change, tags):
    """Datagrams/s offering 1.5 x `ceiling` tag updates/s, `change` of `tags` changing in each."""
    return max(100, round(1.5 * ceiling / max(1, round(change * tags))))


def ratio_text(ratio, meets):
    """The ratio to 2 decimals, or to as many more as it takes for the figure shown to fall on
    the same side of the target (`meets`, a test of a ratio): a 0.8998 is shown neither as 0.90
    nor as 0.900 next to 'no'."""
    for decimals in range(2, 7):
        text = f"{ratio:.{decimals}f}"
        if meets(float(text)) == meets(ratio):
            return text
    return text


def median_round(results):
    """results: (ratio, ...) tuples, one per paired round; the one of median ratio."""
    return sorted(results, key=lambda r: r[0])[len(results) // 2]
