"""What the report says of the machine and the software measured."""

import os
import platform
import subprocess

from benchlib.util import BUILD, ROOT


def description():
    """CPU model and core count (and the kernel)."""
    model = "unknown"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    model = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return (f"{os.cpu_count()} CPUs ({len(os.sched_getaffinity(0))} usable), {model}, "
            f"Linux {platform.release()}")


def build_type():
    """The CMake build type of the tree measured (bench/run.sh builds Release; a tree given in
    EIP2MQTT_BENCH_BUILD may be another)."""
    try:
        with open(os.path.join(BUILD, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("CMAKE_BUILD_TYPE:"):
                    return line.split("=", 1)[1].strip() or "no build type"
    except OSError:
        pass
    return "build type unknown"


def source_revision():
    """The commit of the source tree measured (`git describe`), `-dirty` when it had edits:
    bench/run.sh builds the gateway from this tree just before the run."""
    try:
        out = subprocess.run(["git", "-C", ROOT, "describe", "--always", "--dirty", "--abbrev=7"],
                             capture_output=True, text=True, timeout=5)
    except (OSError, subprocess.TimeoutExpired):
        return "unknown"
    return out.stdout.strip() or "unknown (not a git checkout)"


def mosquitto_version():
    out = subprocess.run(["mosquitto", "-h"], capture_output=True, text=True, timeout=5)
    first = (out.stdout or out.stderr).splitlines()
    return first[0].split()[-1] if first else "?"
