"""The report: the table's rows as the scenarios give them, the machine they ran on, and the
markdown file (bench/results/latest.md, quick.md or partial.md)."""

import datetime
import os
import platform
import subprocess

from benchlib.util import BUILD, GATEWAY, RESULTS, ROOT


class Report:
    def row(self, figure, gateway, baseline, ratio, target, met):
        self.rows.append((figure, gateway, baseline, ratio, target, met))
        print(f"  {figure}: {gateway} | {baseline} | {ratio} | {target} | {met}", flush=True)

    def report(self, command):
        lines = [
            "# eip2mqtt benchmark results",
            "",
            f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC}",
            f"- machine: {machine()}",
            f"- load average at the end (1/5/15 min): "
            f"{' / '.join(f'{x:.1f}' for x in os.getloadavg())} (shared machine: other work "
            "shows here and in the noisier rows)",
            f"- command: `{command}`",
            f"- gateway: `{os.path.relpath(GATEWAY, ROOT)}` ({build_type()}); Mosquitto "
            f"{mosquitto_version()} on 127.0.0.1; subscriber: bench/mqtt_counter (libmosquitto)",
            "",
            "| figure | gateway | baseline (same run) | ratio | target | met? |",
            "|---|---|---|---|---|---|",
        ]
        for r in self.rows:
            lines.append("| " + " | ".join(str(c) for c in r) + " |")
        if self.notes:
            lines += ["", "Notes:"] + [f"- {n}" for n in self.notes]
        text = "\n".join(lines) + "\n"
        os.makedirs(RESULTS, exist_ok=True)
        name = "quick.md" if self.quick else "partial.md" if self.only else "latest.md"
        with open(os.path.join(RESULTS, name), "w") as f:
            f.write(text)
        print()
        print(text)


def machine():
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


def mosquitto_version():
    out = subprocess.run(["mosquitto", "-h"], capture_output=True, text=True, timeout=5)
    first = (out.stdout or out.stderr).splitlines()
    return first[0].split()[-1] if first else "?"
