"""time_vs_samples: GPU time against AO samples per pixel, a line per (kernel, API).

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line, series_label
from .plotting import pick_slice

NAME = "time_vs_samples"


def draw(c):
    fixed, by_series = pick_slice(c.records, "samples")
    if not by_series:
        return c.skip("time_vs_samples", "no configurations that differ only in sample count")
    fig, ax = c.figure()
    xs_all, ys_all = set(), []
    for key, pts in by_series.items():
        xs = list(pts)
        ys = [pts[x]["ms"] for x in xs]
        xs_all.update(xs)
        ys_all += ys
        ax.plot(xs, ys, label=series_label(key), **c.style(key))
    ax.set_xscale("log", base=2)
    ticks = sorted(xs_all)
    ax.set_xticks(ticks)
    ax.set_xticklabels([str(t) for t in ticks])
    ax.minorticks_off()
    ax.set_xlim(min(ticks) / 1.25, max(ticks) * 1.25)
    ax.set_xlabel("samples per pixel (log2 scale)")
    c.ms_axis(ax, ys_all)
    c.finish("time_vs_samples", fig, ax, "AO GPU time vs sample count", fixed_line(fixed),
             legend_kw=dict(loc="upper left"))
