"""time_vs_samples: AO pipeline time against AO samples per pixel, a line per (kernel, API).

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line
from .plotting import pick_slice, plot_series

NAME = "time_vs_samples"


def draw(c):
    fixed, by_series = pick_slice(c.records, "samples")
    if not by_series:
        return c.skip("time_vs_samples", "no configurations that differ only in sample count")
    fig, ax = c.figure()
    ticks, ys_all, points = plot_series(c, ax, by_series)
    ax.set_xscale("log", base=2)
    ax.set_xticks(ticks)
    ax.set_xticklabels([str(t) for t in ticks])
    ax.minorticks_off()
    ax.set_xlim(min(ticks) / 1.25, max(ticks) * 1.25)
    ax.set_xlabel("samples per pixel (log2 scale)")
    recs = [r for pts in by_series.values() for r in pts.values()]
    c.ms_axis(ax, ys_all, recs)
    c.finish("time_vs_samples", fig, ax, "AO time vs sample count", fixed_line(fixed),
             legend_kw=dict(loc="upper left"), drawn=recs, extra={"points": points})
