"""Network namespaces a scenario makes for itself (scenario 18's fleet), as the tests'
NetNamespace does: `ip netns add`, commands run inside with `ip netns exec` (which execs them:
a process's pid is the program's own), and sockets opened inside from a thread that entered the
namespace (setns), so that this process can reach what listens there. Addresses are given only
inside the namespaces made here; the root namespace's network is left as it was. Needs root."""

import ctypes
import os
import socket
import subprocess
import threading

IP = "/usr/sbin/ip"
CLONE_NEWNET = 0x40000000
_libc = ctypes.CDLL(None, use_errno=True)


def unavailable():
    """Why namespaces cannot be made here ("" when they can)."""
    if os.geteuid() != 0:
        return "network namespaces need root (CAP_NET_ADMIN, CAP_SYS_ADMIN)"
    if not os.access(IP, os.X_OK):
        return f"{IP} is missing (iproute2; tools/install-deps.sh installs it)"
    return ""


def ip(*args, timeout=10):
    """`ip ARGS` to its end; raises with its output when it fails."""
    out = subprocess.run([IP, *args], capture_output=True, text=True, timeout=timeout)
    if out.returncode != 0:
        raise RuntimeError(f"ip {' '.join(args)}: {(out.stderr or out.stdout).strip()}")
    return out.stdout


class NetNamespace:
    def __init__(self, name):
        """Adds namespace `name` with its loopback up."""
        self.name = name
        ip("netns", "add", name)
        self.added = True
        self.ip("link", "set", "lo", "up")

    def ip(self, *args):
        """`ip -n NAME ARGS`: an `ip` command applied inside."""
        return ip("-n", self.name, *args)

    def inside(self, argv):
        """`argv` run inside (for Popen)."""
        return [IP, "netns", "exec", self.name, *map(str, argv)]

    def connects(self, host, port, timeout=0.3):
        """Whether a TCP connection to host:port opens from inside (a thread of its own enters
        the namespace, makes the connection and ends)."""
        result = []

        def attempt():
            fd = os.open(f"/var/run/netns/{self.name}", os.O_RDONLY | os.O_CLOEXEC)
            try:
                if _libc.setns(fd, CLONE_NEWNET) != 0:
                    return
            finally:
                os.close(fd)
            try:
                socket.create_connection((host, port), timeout=timeout).close()
                result.append(True)
            except OSError:
                pass

        thread = threading.Thread(target=attempt, daemon=True)
        thread.start()
        thread.join(timeout + 2)
        return bool(result)

    def delete(self):
        """Deletes it (its ends of veth pairs, and a bridge in it, go with it); once."""
        if self.added:
            self.added = False
            ip("netns", "del", self.name)


class Segment:
    """A hub namespace holding a bridge at `prefix`.1/24, and a namespace per member joined to
    the bridge by a veth pair, the member's end at `prefix`.(10 + i), its loopback up. Used as
    a context: every namespace is deleted on the way out, whatever happened."""

    def __init__(self, tag, prefix):
        self.tag, self.prefix = tag, prefix
        self.hub = None
        self.members = []

    @property
    def hub_address(self):
        return f"{self.prefix}.1"

    def __enter__(self):
        try:
            self.hub = NetNamespace(f"{self.tag}-hub")
            self.hub.ip("link", "add", "br0", "type", "bridge")
            self.hub.ip("addr", "add", f"{self.hub_address}/24", "dev", "br0")
            self.hub.ip("link", "set", "br0", "up")
        except Exception:
            self.close()
            raise
        return self

    def add_member(self):
        """A new member namespace on the bridge: (namespace, its address)."""
        i = len(self.members)
        member = NetNamespace(f"{self.tag}-g{i}")
        self.members.append(member)
        address = f"{self.prefix}.{10 + i}"
        self.hub.ip("link", "add", f"g{i}", "type", "veth", "peer", "name", "eth0", "netns",
                    member.name)
        self.hub.ip("link", "set", f"g{i}", "master", "br0", "up")
        member.ip("addr", "add", f"{address}/24", "dev", "eth0")
        member.ip("link", "set", "eth0", "up")
        return member, address

    def close(self):
        errors = []
        for ns in self.members + ([self.hub] if self.hub else []):
            try:
                ns.delete()
            except Exception as e:  # the others are deleted still
                errors.append(str(e))
        self.members = []
        if errors:
            raise RuntimeError("; ".join(errors))

    def __exit__(self, *exc):
        self.close()
        return False
