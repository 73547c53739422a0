"""The builds a run measures: this tree's gateway and, with --against-binary, an earlier one
(the regression guard). Scenarios run each build in turn, the order alternating from round
to round, and a build that cannot run a scenario's configuration is reported as such."""

import hashlib
import os
import subprocess
import tempfile

from benchlib.util import stop


class NotInBuild(Exception):
    """The build cannot run this configuration (its `check -c` refuses it, or it did not
    start)."""

    def __init__(self, build, reason):
        super().__init__(f"{build.label}: {reason}")
        self.build = build
        self.reason = reason


class Build:
    def __init__(self, label, gateway, new):
        self.label = label
        self.gateway = gateway
        self.new = new  # the build under test (its failures fail the run)
        self.checked = {}  # digest of a configuration -> refusal, or "" when accepted
        self.keys = {}  # a YAML `eip:` key -> whether this build reads it

    def require(self, config_path):
        """Raises NotInBuild unless `check -c config_path` accepts the configuration. The
        build under test is not asked: a configuration it refuses is the benchmark's error."""
        if self.new:
            return
        with open(config_path, "rb") as f:
            digest = hashlib.sha1(f.read()).hexdigest()
        if digest not in self.checked:
            out = subprocess.run([self.gateway, "check", "-c", config_path],
                                 capture_output=True, text=True, timeout=120)
            text = (out.stderr.strip() or out.stdout.strip()).splitlines()
            self.checked[digest] = "" if out.returncode == 0 else \
                (text[0] if text else f"check exited {out.returncode}")
        if self.checked[digest]:
            raise NotInBuild(self, self.checked[digest])

    def reads_eip_key(self, key, value):
        """Whether `check -c` accepts `eip.{key}: {value}` (an earlier build may not know the
        key), asked once per key."""
        if key not in self.keys:
            with tempfile.NamedTemporaryFile("w", suffix=".yaml") as f:
                f.write(f"eip: {{ {key}: {value} }}\n"
                        "exchanges:\n"
                        "  - { name: k, direction: produce, producer_id: 10.0.0.2, exchange_id: 1,\n"
                        "      destination: 127.0.0.1, period_ms: 100,\n"
                        "      tags: [ { name: t, address: '0.0', type: dint } ] }\n")
                f.flush()
                out = subprocess.run([self.gateway, "check", "-c", f.name],
                                     capture_output=True, text=True, timeout=60)
            self.keys[key] = out.returncode == 0
        return self.keys[key]

    def start_failed(self, proc, log_path):
        """Raises NotInBuild for this earlier build's gateway `proc` that did not come online
        (stopped if it still runs): the reason is its log's last line. The build under test's
        failures stay errors of the run."""
        if self.new:
            return
        ended = proc.poll() is not None
        stop(proc)
        reason = f"exited {proc.returncode}" if ended else "did not come online"
        if os.path.exists(log_path):
            with open(log_path, errors="replace") as f:
                lines = [line.strip() for line in f if line.strip()]
            reason = lines[-1] if lines else reason
        raise NotInBuild(self, reason)


def in_order(builds, round_index):
    """The builds in the order round `round_index` runs them: the build under test first in
    even rounds, last in odd ones, so that neither always runs on a machine the other has just
    warmed (or loaded)."""
    return list(builds) if round_index % 2 == 0 else list(reversed(builds))
