"""full_vs_half: Full against half resolution bars, the speed-up (full / half) above each pair.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line
from .plotting import label_pairs, paired, pick_slice

NAME = "full_vs_half"


def speedups(records):
    """Full/half speed-up per (kernel, api) in the slice the full_vs_half chart
    draws: {(kernel, api): (full_ms, half_ms, full_ms / half_ms)}."""
    return paired(records, "res", "full", "half", lambda full, half: full / half)


def draw(c):
    fixed, _ = pick_slice(c.records, "res")
    sp = speedups(c.records)
    if not sp:
        return c.skip("full_vs_half", "no configuration measured at both full and half resolution")
    fig, ax = c.figure(width=max(6.5, 1.3 * len(sp) + 3))
    keys = list(sp)
    w = 0.38
    fulls = [sp[k][0] for k in keys]
    halves = [sp[k][1] for k in keys]
    xs = list(range(len(keys)))
    ax.bar([x - w / 2 for x in xs], fulls, w, label="full resolution", color="#3b6ea8", zorder=3)
    ax.bar([x + w / 2 for x in xs], halves, w, label="half resolution (AO at ¼ pixels + upsample)",
           color="#9cc3e6", edgecolor="#3b6ea8", zorder=3)
    top = max(fulls + halves)
    labels_written = label_pairs(ax, sp)
    ax.set_ylim(0, top * 1.22)
    ax.set_ylabel("GPU time (ms)")
    ax.set_xlabel("kernel and API   (number above each pair: speed-up = full time / half time)")
    c.finish("full_vs_half", fig, ax, "Full vs half resolution AO", fixed_line(fixed),
             legend_kw=dict(loc="upper left"), extra={"labels": labels_written})
