"""time_vs_megapixels: AO pipeline time against image size, with a linear fit through the origin, and the cost
per megapixel beside it (flat = linear in pixels).

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from . import spread
from .labels import fixed_line, series_label, time_label
from .plotting import pick_slice, spread_point, whiskers

NAME = "time_vs_megapixels"


def fit_through_origin(xs, ys):
    """Least-squares y = slope * x; returns (slope, R²) with R² against the
    mean (so a line that misses the points scores low, even negative)."""
    sxx = sum(x * x for x in xs)
    slope = sum(x * y for x, y in zip(xs, ys)) / sxx if sxx else float("nan")
    mean = sum(ys) / len(ys)
    ss_tot = sum((y - mean) ** 2 for y in ys)
    ss_res = sum((y - slope * x) ** 2 for x, y in zip(xs, ys))
    r2 = 1.0 - ss_res / ss_tot if ss_tot > 0 else float("nan")
    return slope, r2


def draw(c):
    fixed, by_series = pick_slice(c.records, "size")
    if not by_series:
        return c.skip("time_vs_megapixels", "no configurations that differ only in image size")
    fig, (ax, ax2) = c.plt.subplots(1, 2, figsize=(11, 5.4), gridspec_kw=dict(width_ratios=(1.35, 1)))
    sizes = set()
    xmax = ymax = 0
    fits = {}
    per_mp = []
    recs_all, points = [], {}
    for key, pts in by_series.items():
        st = c.style(key)
        xs = [w * h / 1e6 for (w, h) in pts]
        recs = list(pts.values())
        ys = [r["ms"] for r in recs]
        recs_all += recs
        points[series_label(key)] = [spread_point(s, r) for s, r in pts.items()]
        sizes.update(pts)
        slope, r2 = fit_through_origin(xs, ys)
        fits[series_label(key)] = {"ms_per_mp": slope, "r2": r2}
        ax.plot(xs, ys, linestyle="none", marker=st["marker"], markersize=7, color=st["color"], zorder=3,
                label=f"{series_label(key)}:  {slope:.3g} ms/MP,  R²={r2:.3f}")
        whiskers(ax, xs, ys, recs, ecolor=st["color"], capsize=3.5)
        xe = max(xs) * 1.05
        ax.plot([0, xe], [0, slope * xe], linestyle="--", linewidth=1.2, color=st["color"], alpha=0.8, zorder=2)
        xmax, ymax = max(xmax, xe), max(ymax, max(r.get("q75") or r["ms"] for r in recs), slope * xe)
        # right: cost per megapixel; flat means time is linear in pixels
        ratios = [y / x for x, y in zip(xs, ys)]
        per_mp += ratios
        ax2.plot(xs, ratios, color=st["color"], linestyle=st["linestyle"], marker=st["marker"],
                 markersize=6, linewidth=1.6, zorder=3)
        ax2.axhline(slope, color=st["color"], linestyle=":", linewidth=1.1, alpha=0.9, zorder=2)
    ax.plot([], [], linestyle="--", color="#555555", label="linear fit through origin")
    ax.set_xlim(0, xmax * 1.02)
    ax.set_ylim(0, ymax * 1.08)
    ax.set_xlabel("megapixels (output image)")
    ax.set_ylabel(time_label(recs_all))
    ax.set_title("measured time (markers) and linear fit through the origin (dashed)", loc="left", fontsize=9)
    ss = sorted(sizes, key=lambda s: s[0] * s[1])
    ax2.set_xscale("log")
    mps = [w * h / 1e6 for w, h in ss]
    ax2.set_xticks(mps)
    ax2.set_xticklabels([f"{w}x{h}\n{w * h / 1e6:.2g} MP" for w, h in ss], fontsize=8)
    ax2.minorticks_off()
    ax2.set_xlim(min(mps) / 1.6, max(mps) * 1.6)
    ax2.set_ylim(0, max(per_mp) * 1.15)
    ax2.set_xlabel("image size (megapixels, log scale)")
    ax2.set_ylabel("time per megapixel (ms/MP)")
    ax2.set_title("cost per megapixel (dotted: fitted slope); flat = linear", loc="left", fontsize=9)
    c.finish("time_vs_megapixels", fig, [ax, ax2], "AO time vs image size", fixed_line(fixed),
             legend_kw=dict(loc="upper left", ncol=1, fontsize=8.5), drawn=recs_all,
             extra={"fits": fits, "points": points})
