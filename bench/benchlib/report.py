"""The report: the table's rows as the scenarios give them, with the earlier build's figures
beside them (--against-binary), the CPU per publication of the per-tag rows, the machine they
ran on, and the markdown file (bench/results/latest.md, quick.md or partial.md)."""

import datetime
import os

from benchlib import machine
from benchlib.util import GATEWAY, RESULTS, ROOT, median

CPU_ROLES = ("gateway", "load generator", "broker", "subscriber")


def ratios_text(ratios):
    text = f"{median(ratios):.2f}"
    if len(ratios) > 1:
        text += " (rounds: " + ", ".join(f"{r:.2f}" for r in ratios) + ")"
    return text


class Report:
    def row(self, figure, gateway, baseline, ratio, target, met, against=None):
        """One row of the table; `against`: the earlier build's two cells (versus), which
        every row carries when the run has an earlier build."""
        cells = [figure, gateway, baseline, ratio, target, met]
        if self.against:
            if against is None:
                raise RuntimeError(f"a row without {self.against.label}'s figure: {figure}")
            cells += list(against)
        self.rows.append(tuple(cells))
        print("  " + figure + ": " + " | ".join(str(c) for c in cells[1:]), flush=True)

    def versus(self, rounds, value, shown=None, fmt="{:,.0f}".format):
        """The earlier build's cells of a row from `rounds` ({build: result} of each round):
        its figure (`shown` of its results, or `fmt` of its median value) and the ratio this
        build / it, the median over rounds of each round's ratio. None without an earlier
        build; "not in LABEL" where it cannot run the scenario."""
        if self.against is None:
            return None
        label = self.against.label
        new = [r[self.build] for r in rounds]
        old = [r.get(self.against) for r in rounds]
        if any(o is None for o in old):
            return f"not in {label}", "-"
        text = shown(old) if shown else fmt(median([value(o) for o in old]))
        ratios = [value(n) / value(o) for n, o in zip(new, old) if value(o)]
        if ratios:
            return text, ratios_text(ratios)
        return text, "- (both 0)" if all(value(n) == 0 for n in new) else f"- ({label} 0)"

    def cpu_row(self, figure, run, samples):
        """CPU per publication of one run of a per-tag row, every round's."""
        self.cpu_rows.append((figure, run, [s for s in samples if s]))

    def header(self, command):
        lines = [
            "# eip2mqtt benchmark results",
            "",
            f"- date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M UTC}",
            f"- machine: {machine.description()}",
            f"- bare Paho on this machine, this run: {self.paho_summary()}",
            f"- load average at the end (1/5/15 min): "
            f"{' / '.join(f'{x:.1f}' for x in os.getloadavg())} (shared machine: other work "
            "shows here and in the noisier rows)",
            f"- command: `{command}`",
            f"- gateway: `{shown_path(GATEWAY)}` ({machine.build_type()}, source "
            f"{machine.source_revision()}); Mosquitto "
            f"{machine.mosquitto_version()} on 127.0.0.1; subscriber: bench/mqtt_counter "
            "(libmosquitto)",
        ]
        if self.against:
            label = self.against.label
            lines.append(
                f"- against: {label} (`{shown_path(self.against.gateway)}`), in the same run: each "
                f"scenario runs both builds in alternating rounds (this build first in round 1, "
                f"{label} first in round 2, ...), beside the same round's baselines; "
                f"`this / {label}` is the median of the rounds' ratios")
        return lines

    def paho_summary(self):
        parts = [f"QoS {qos} {rate:,.0f} messages/s ({broker})"
                 for (qos, broker), rate in sorted(self.paho_rates.items())]
        return ("; ".join(parts) + " (bench/paho_publisher, 100 topics, median round)"
                if parts else "not measured")

    def table(self):
        head = "| figure | gateway | baseline (same run) | ratio | target | met? |"
        rule = "|---|---|---|---|---|---|"
        if self.against:
            head += f" {self.against.label} | this / {self.against.label} |"
            rule += "---|---|"
        return [head, rule] + ["| " + " | ".join(str(c) for c in r) + " |" for r in self.rows]

    def cpu_table(self):
        if not self.cpu_rows:
            return []
        lines = [
            "", "## CPU per publication, per-tag rows", "",
            "CPU time per publication counted, over the loaded part of each run (1 s after the "
            "load starts to 0.5 s before it ends, a quarter of a shorter run at each end; "
            "sampled from /proc every 0.25 s, or a tenth of a shorter run), median of the "
            "rounds: the machine's busy time, "
            "then each process's (for bare Paho, its publisher in the gateway column; for the "
            "Node-RED flow, its node process; in the overload rows, the busiest threads by name "
            "in parentheses, us each). Unlike a rate, it does not depend on who else runs.", "",
            "| figure | run | publications/s | machine busy (idle) | gateway | load generator "
            "| broker | subscriber |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for figure, run, samples in self.cpu_rows:
            lines.append("| " + " | ".join([figure, run] + cpu_cells(samples)) + " |")
        return lines

    def report(self, command):
        lines = self.header(command) + [""] + self.table()
        if self.notes:
            lines += ["", "Notes:"] + [f"- {n}" for n in self.notes]
        lines += self.cpu_table()
        text = "\n".join(lines) + "\n"
        os.makedirs(RESULTS, exist_ok=True)
        name = "quick.md" if self.quick else "partial.md" if self.only else "latest.md"
        with open(os.path.join(RESULTS, name), "w") as f:
            f.write(text)
        print()
        print(text)


def shown_path(path):
    """`path` from the repository's root when it lies under it."""
    relative = os.path.relpath(path, ROOT)
    return path if relative.startswith("..") else relative


def cpu_cells(samples):
    """The CPU table's figure cells from each round's CpuSampler.per_publication."""
    if not samples:
        return ["-"] * (2 + len(CPU_ROLES))

    def middle(key):
        values = [s[key] for s in samples if key in s]
        return median(values) if values else None

    cells = [f"{middle('rate'):,.0f}", f"{middle('machine'):.1f} us (idle {middle('idle'):.0f} %)"]
    for role in CPU_ROLES:
        value, shown = middle(role), role
        if role == "gateway" and value is None:
            # Bare Paho's run: its publisher in that column; a peer's run: the peer.
            shown = next((r for r in ("publisher", "peer") if middle(r) is not None), role)
            value = middle(shown)
        cells.append("-" if value is None else f"{value:.1f} us" + threads_note(samples, shown))
    return cells


def threads_note(samples, role, most=5):
    """ " (thread a us, ...)": the `most` busiest threads of `role` (by name), median of the
    rounds, where the run sampled it thread by thread."""
    rounds = [s[role + " threads"] for s in samples if s.get(role + " threads")]
    if not rounds:
        return ""
    names = {name for r in rounds for name in r}
    per = {name: median([r.get(name, 0.0) for r in rounds]) for name in names}
    busiest = [(name, us) for name, us in sorted(per.items(), key=lambda kv: -kv[1])[:most]
               if us > 0]
    return " (" + ", ".join(f"{name} {us:.1f}" for name, us in busiest) + ")" if busiest else ""
