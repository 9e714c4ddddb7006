"""full_vs_half: Full against half resolution bars with each one's spread, the speed-up (full / half) above each
pair with its range, or marked where the two spreads overlap.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line
from .plotting import bar_pairs, paired, pick_slice

NAME = "full_vs_half"


def speedups(records):
    """Full/half speed-up per (kernel, api) in the slice the full_vs_half chart
    draws: {(kernel, api): (full record, half record, spread.ratio_entry)};
    the entry's "ratio" is full ms / half ms."""
    return paired(records, "res", "full", "half")


def draw(c):
    fixed, _ = pick_slice(c.records, "res")
    sp = speedups(c.records)
    if not sp:
        return c.skip("full_vs_half", "no configuration measured at both full and half resolution")
    fig, ax = c.figure(width=max(6.5, 1.3 * len(sp) + 3))
    vals, labels_written, ratios = bar_pairs(c, ax, sp, ("full resolution", "half resolution (AO at ¼ pixels + upsample)"),
                                             ("#3b6ea8", "#9cc3e6"), edge="#3b6ea8")
    drawn = [r for k in sp for r in sp[k][:2]]
    c.ms_axis(ax, vals, drawn)
    ax.set_ylim(0, max(vals) * 1.3)
    ax.set_xlabel("kernel and API   (above each pair: speed-up = full / half, and its range "
                  "from the two spreads)")
    c.finish("full_vs_half", fig, ax, "Full vs half resolution AO", fixed_line(fixed),
             legend_kw=dict(loc="lower left", bbox_to_anchor=(0, 1.0), ncol=2, frameon=False), drawn=drawn, extra={"labels": labels_written, "ratios": ratios})
