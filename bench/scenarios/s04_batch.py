"""Scenario 4: tag updates/s carried in batch mode (`_values`) and by Sparkplug B DDATA,
against the gateway's per-tag figure of scenario 2."""

from benchlib.report import ratios_text
from benchlib.util import SHAPES, TAGS, median, median_round


def updates_shown(got):
    return f"{got['update_rate']:,.0f} ({got['rate']:,.0f} msgs/s)"


def against_cells(bench, runs):
    """The earlier build's cells of a row measured once per build."""
    return bench.versus([runs], lambda got: got["update_rate"],
                        shown=lambda old: updates_shown(old[0]))


def batch_rows(bench):
    print("[4] batch mode, QoS 1", flush=True)
    per_tag = bench.ceilings.get(("gw", 1)) or bench.paho_ceiling(1)
    # Every tag changing. The 10 x target is the 100-tag exchange's; with 10 tags a
    # datagram, a `_values` message carries 10 updates at most, and it shares the message
    # rate with the tag topics: in turn, or first (batch_first).
    for (exchanges, tags), batch in ((SHAPES[0], True), (SHAPES[1], True),
                                     (SHAPES[1], "first")):
        # Offer 2 x the 1 x 100 target: 20 x the per-tag figure in tag updates.
        runs = bench.per_build(0, lambda build: bench.gateway_rate(
            f"g4e{exchanges}{'f' if batch == 'first' else ''}", 1, 1.0, 20 * per_tag / 1.5,
            batch=batch, exchanges=exchanges, tags=tags, build=build))
        got = runs[bench.build]
        ratio = got["update_rate"] / per_tag if per_tag else 0
        large = (exchanges, tags) == SHAPES[0]
        bench.row(f"tag updates/s carried in batch mode (_values), QoS 1, {exchanges} x {tags} "
                  f"tags{', batch_first' if batch == 'first' else ''}", updates_shown(got),
                  f"{per_tag:,.0f} (gateway per-tag QoS 1, 1 x {TAGS} tags)", f"{ratio:.1f}",
                  ">= 10" if large else "-", ("yes" if ratio >= 10 else "no") if large else "-",
                  against_cells(bench, runs))


def sparkplug_rows(bench):
    print("[4] Sparkplug B DDATA, QoS 0 (the only QoS Sparkplug B 3.0 allows for DATA)", flush=True)
    for qos in (0,):
        per_tag = bench.ceilings.get(("gw", qos))
        baseline = "gateway per-tag JSON"
        if per_tag is None:  # --only without scenarios 2 and 3
            per_tag, baseline = bench.paho_ceiling(qos), "bare Paho per-tag"
        runs = bench.per_build(0, lambda build: bench.gateway_rate(
            f"g4s{qos}", qos, 1.0, 20 * per_tag / 1.5, sparkplug=True, build=build))
        got = runs[bench.build]
        ratio = got["update_rate"] / per_tag if per_tag else 0
        bench.row(f"tag updates/s carried by Sparkplug B DDATA, QoS {qos}", updates_shown(got),
                  f"{per_tag:,.0f} ({baseline} QoS {qos})", f"{ratio:.1f}", ">= 10",
                  "yes" if ratio >= 10 else "no", against_cells(bench, runs))


def scaled_row(bench):
    """`_values` with every tag scaled against the same exchanges unscaled, in paired rounds
    (unscaled first in even rounds); the earlier build, where it knows `scale`, runs the scaled
    configuration beside this one."""
    print("[4] batch mode, every tag scaled, QoS 1", flush=True)
    per_tag = bench.ceilings.get(("gw", 1)) or bench.paho_ceiling(1)
    exchanges, tags = SHAPES[1]

    def measure(scaled, build=None):
        return bench.gateway_rate(f"g4v{'s' if scaled else 'u'}", 1, 1.0, 20 * per_tag / 1.5,
                                  batch=True, exchanges=exchanges, tags=tags, sample=True,
                                  scaled=scaled, build=build)

    rounds = []  # (this build unscaled, {build: scaled})
    for r in range(bench.rounds):
        unscaled = measure(False) if r % 2 == 0 else None
        scaled = bench.per_build(r, lambda build: measure(True, build))
        rounds.append((unscaled or measure(False), scaled))
    ratios = [s[bench.build]["update_rate"] / u["update_rate"] for u, s in rounds
              if u["update_rate"]]
    middle = median_round([(ratio, r) for ratio, r in zip(ratios, rounds)]) if ratios else None
    ratio, (unscaled, scaled) = middle if middle else (0.0, rounds[0])
    cpu = [s[bench.build]["cpu"]["gateway"] / u["cpu"]["gateway"] for u, s in rounds
           if s[bench.build]["cpu"] and u["cpu"] and u["cpu"].get("gateway")]
    cpu_note = f"; gateway CPU/update {median(cpu):.2f} x unscaled" if cpu else ""
    bench.row(f"tag updates/s carried in batch mode (_values), every tag scaled (linear), QoS 1, "
              f"{exchanges} x {tags} tags{bench.rounds_label()}",
              updates_shown(scaled[bench.build]) + cpu_note,
              f"{updates_shown(unscaled)} (the same exchanges unscaled, same run)",
              ratios_text(ratios) if ratios else "-", ">= 0.95",
              "yes" if ratio >= 0.95 else "no",
              bench.versus([s for _, s in rounds], lambda g: g["update_rate"]))


def run(bench):
    batch_rows(bench)
    scaled_row(bench)
    sparkplug_rows(bench)
