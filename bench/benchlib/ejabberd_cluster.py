"""A cluster of Debian 12's ejabberd 23.01 nodes (`mod_mqtt`: MQTT 5 and 3.1.1) on this machine,
started, joined and stopped by the benchmark, as the tests' EjabberdCluster does
(tests/support/ejabberd_cluster.cpp, broker_cluster.cpp).

Each node runs `ejabberdctl foreground` (as the `ejabberd` user: ejabberdctl switches to it when
started by root) with a directory of its own (configuration, spool, logs), only an MQTT
listener, anonymous authentication (any user name, a non-empty password: LOGIN), and the
cluster's epmd and cookie in its own ejabberdctl.cfg. Everything runs inside one network
namespace the scenario made (`netns`, a benchlib.netns.NetNamespace), where the ports are the
well-known ones (epmd 4369, MQTT 1883 + node) since nothing else listens there: the listener is
on 0.0.0.0 *of that namespace*, reached from the namespace's loopback and from the segment its
bridge serves, never from the machine's own network. Used as a context: started on entry,
every node and the epmd stopped on the way out, whatever happened."""

import os
import pwd
import shutil
import signal
import subprocess
import tempfile
import time

from benchlib.util import stop

EJABBERDCTL = "/usr/sbin/ejabberdctl"
EPMD = "/usr/bin/epmd"
LOGIN = ("eip2mqtt", "cluster")  # user name, password (anonymous: any name, a non-empty one)
EPMD_PORT = 4369
FIRST_MQTT_PORT = 1883
# An Erlang VM and its ejabberd start in seconds on an idle machine; far more with three
# starting at once on a loaded one (the tests allow as much).
START_S = 180
COMMAND_S = 90


def unavailable():
    """Why a cluster cannot be started here ("" when it can)."""
    if not os.access(EJABBERDCTL, os.X_OK) or not os.access(EPMD, os.X_OK):
        return "ejabberd is not installed (tools/install-deps.sh installs it)"
    if os.geteuid() != 0:
        return "ejabberd's nodes are started as root (ejabberdctl then runs them as ejabberd)"
    return ""


def poll_until(done, timeout, every=0.1):
    """done() every `every` s until it holds (True) or `timeout` s passed (False)."""
    deadline = time.monotonic() + timeout
    while True:
        if done():
            return True
        if time.monotonic() > deadline:
            return False
        time.sleep(every)


def alive(pid):
    """Whether process `pid` runs (a zombie does not)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except (OSError, IndexError):
        return False


class Node:
    def __init__(self, name, path, port):
        self.name, self.dir, self.port = name, path, port
        self.process = None  # the launcher: ejabberdctl foreground
        self.vm = 0  # beam.smp, from the pid file the node writes


class EjabberdCluster:
    def __init__(self, netns, nodes=3, loglevel="info"):
        self.netns = netns
        self.loglevel = loglevel
        self.cookie = f"eip2mqttbench{os.getpid()}"
        self.dir = tempfile.mkdtemp(prefix="eip2mqtt-bench-ejabberd-", dir="/tmp")
        os.chmod(self.dir, 0o755)  # the ejabberd user reaches its nodes' directories
        self.epmd = None
        self.nodes = [Node(f"e2mbench{os.getpid()}n{i}@localhost", os.path.join(self.dir, f"n{i}"),
                           FIRST_MQTT_PORT + i) for i in range(nodes)]

    def __enter__(self):
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc):
        self.stop()
        return False

    def vm_pids(self):
        return [node.vm for node in self.nodes]

    def ctl(self, node, *command):
        """ejabberdctl's command line for `node`, run inside the namespace."""
        return self.netns.inside([
            EJABBERDCTL, "--node", node.name, "--config-dir", node.dir, "--config",
            os.path.join(node.dir, "ejabberd.yml"), "--ctl-config",
            os.path.join(node.dir, "ejabberdctl.cfg"), "--logs", os.path.join(node.dir, "logs"),
            "--spool", os.path.join(node.dir, "spool"), *command])

    def start(self):
        """Every node started at once, the others joined to the first, all listed as members."""
        self.epmd = subprocess.Popen(
            self.netns.inside([EPMD, "-port", EPMD_PORT, "-address", "127.0.0.1"]),
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        if not poll_until(lambda: self.netns.connects("127.0.0.1", EPMD_PORT), 10):
            raise RuntimeError("epmd did not start")
        for node in self.nodes:
            self.launch(node)
        for node in self.nodes:
            self.wait_started(node)
        for node in self.nodes[1:]:
            self.command(node, "join_cluster", self.nodes[0].name)
        for node in self.nodes:  # a node that joined restarts its ejabberd (in the same VM)
            if not poll_until(lambda: self.netns.connects("127.0.0.1", node.port), START_S):
                raise RuntimeError(f"{node.name} takes no MQTT connection after joining")
            self.read_vm(node)
        listed = self.command(self.nodes[0], "list_cluster")
        missing = [node.name for node in self.nodes if node.name not in listed]
        if missing:
            raise RuntimeError(f"not in the cluster: {missing}: {listed}")

    def launch(self, node):
        """Writes the node's files and starts it, without waiting."""
        for sub in ("logs", "spool"):
            os.makedirs(os.path.join(node.dir, sub), exist_ok=True)
        with open(os.path.join(node.dir, "ejabberd.yml"), "w") as f:
            f.write(f"hosts: [localhost]\nloglevel: {self.loglevel}\nauth_method: [anonymous]\n"
                    "anonymous_protocol: login_anon\nlisten:\n"
                    f"  - port: {node.port}\n    ip: \"0.0.0.0\"\n    module: mod_mqtt\n"
                    "    backlog: 1000\nmodules:\n  mod_mqtt: {}\n")
        # ejabberdctl reads this after its arguments: the node's own pid file, and for the node
        # and every command sent to it the cluster's epmd and cookie.
        with open(os.path.join(node.dir, "ejabberdctl.cfg"), "w") as f:
            f.write(f"EJABBERD_PID_PATH={node.dir}/pid\n"
                    f"ERL_OPTIONS=\"-env ERL_CRASH_DUMP_BYTES 0 -setcookie {self.cookie}\"\n"
                    f"ERL_EPMD_PORT={EPMD_PORT}\nexport ERL_EPMD_PORT\n")
        user = pwd.getpwnam("ejabberd")
        for where, dirs, files in os.walk(node.dir):
            for path in [where] + [os.path.join(where, n) for n in dirs + files]:
                os.chown(path, user.pw_uid, user.pw_gid)
        out = open(os.path.join(node.dir, "output.log"), "w")
        node.process = subprocess.Popen(self.ctl(node, "foreground"), stdout=out,
                                        stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                                        start_new_session=True,
                                        env={**os.environ, "ERL_EPMD_PORT": str(EPMD_PORT)})
        out.close()

    def read_vm(self, node):
        try:
            with open(os.path.join(node.dir, "pid")) as f:
                node.vm = int(f.read().strip() or 0)
        except (OSError, ValueError):
            node.vm = 0
        return node.vm

    def wait_started(self, node):
        def started():
            if node.process.poll() is not None:
                raise RuntimeError(f"{node.name} ended ({node.process.returncode}): "
                                   f"{self.log(node)}")
            return self.read_vm(node) > 0 and self.netns.connects("127.0.0.1", node.port)

        if not poll_until(started, START_S):
            raise RuntimeError(f"{node.name} did not start within {START_S} s: {self.log(node)}")

    def command(self, node, *command):
        """An ejabberdctl command sent to `node`; its output (raises when it fails)."""
        out = subprocess.run(self.ctl(node, *command), capture_output=True, text=True,
                             timeout=COMMAND_S)
        if out.returncode != 0:
            raise RuntimeError(f"ejabberdctl {' '.join(command)} on {node.name} failed "
                               f"({out.returncode}): {out.stdout[-500:]}{out.stderr[-500:]}")
        return out.stdout

    def logged(self, text):
        """How many lines of each node's ejabberd.log hold `text`."""
        counts = []
        for node in self.nodes:
            try:
                with open(os.path.join(node.dir, "logs", "ejabberd.log"), errors="replace") as f:
                    counts.append(sum(text in line for line in f))
            except OSError:
                counts.append(0)
        return counts

    def log(self, node, tail=1500):
        """The end of the node's ejabberd.log and of what it printed."""
        text = ""
        for name in ("logs/ejabberd.log", "output.log"):
            try:
                with open(os.path.join(node.dir, name), errors="replace") as f:
                    text += f.read()[-tail:]
            except OSError:
                pass
        return text

    def stop(self):
        """SIGTERM to every node's VM (init:stop, a clean stop), SIGKILL to one still running
        20 s later; their launchers, then the epmd; the directory removed."""
        for node in self.nodes:
            if node.vm <= 0:
                self.read_vm(node)
            if node.vm > 0 and alive(node.vm):
                os.kill(node.vm, signal.SIGTERM)
        for node in self.nodes:
            if node.vm > 0 and not poll_until(lambda: not alive(node.vm), 20):
                os.kill(node.vm, signal.SIGKILL)
                poll_until(lambda: not alive(node.vm), 10)
            end_group(node.process)
        stop(self.epmd)
        self.epmd = None
        if os.environ.get("EIP2MQTT_BENCH_KEEP"):
            print(f"kept {self.dir}")
        else:
            shutil.rmtree(self.dir, ignore_errors=True)


def end_group(proc, timeout=10):
    """Waits for `proc` (and kills its process group, when it was given one, if it does not
    end): nothing it started outlives it."""
    if proc is None:
        return
    try:
        proc.wait(timeout=timeout)
        return
    except subprocess.TimeoutExpired:
        pass
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except OSError:
        proc.kill()
    proc.wait(timeout=5)
