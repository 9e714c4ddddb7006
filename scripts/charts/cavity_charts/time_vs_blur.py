"""time_vs_blur: AO pipeline time against the bilateral blur radius, a line per (kernel, API).

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line
from .plotting import pick_slice, plot_series

NAME = "time_vs_blur"


def draw(c):
    fixed, by_series = pick_slice(c.records, "blur")
    if not by_series:
        return c.skip("time_vs_blur", "no configurations that differ only in blur radius")
    fig, ax = c.figure()
    ticks, ys_all, points = plot_series(c, ax, by_series)
    ax.set_xticks(ticks)
    ax.set_xticklabels(["0 (off)" if t == 0 else str(t) for t in ticks])
    ax.set_xlabel("blur radius (px)")
    recs = [r for pts in by_series.values() for r in pts.values()]
    c.ms_axis(ax, ys_all, recs)
    c.finish("time_vs_blur", fig, ax, "AO time vs bilateral blur radius", fixed_line(fixed),
             legend_kw=dict(loc="lower right"), drawn=recs, extra={"points": points})
