"""Shared plotting: which slice of the data a chart draws (pick_slice), and
Canvas, what every chart of the main command draws with (matplotlib set up
once, a colour per kernel, a line style per API, the title block, the
legend, log axes written plainly, and the PNG + SVG written and listed)."""

import os
import sys
import textwrap
from collections import Counter, OrderedDict, defaultdict

from . import spread
from .inputs import DIMS
from .labels import API_NAMES, clock_text, device_line, format_ratio, series_label, time_label

DPI = 150
LEGEND_MAX = 12
# A chart shows at most this many series (lines, or pairs of bars): past it
# colours repeat and lines cannot be told apart; --filter picks which.
MAX_SERIES = 8
# No chart is wider than this: a wider one is unreadable on a screen.
MAX_WIDTH_PX = 2000


def setup_matplotlib():
    """pyplot on the Agg backend (no display)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return matplotlib, plt


def pick_slice(records, vary, series=("kernel", "api"), need=2, prefer=None):
    """The records of one slice of the data: every dimension but `vary` and the
    `series` dimensions fixed at one value. Slices where no series has `need`
    distinct values of `vary` are not considered. Prefers 1920x1080 and the
    compute stage (unless varied), then the slice with most series complete,
    then most points, then the most common values. Returns (fixed dict,
    {series key: {vary value: record}}) or (None, {})."""
    recs = list(records)
    fixed_dims = [d for d in DIMS if d != vary and d not in series]
    freq = {d: Counter(r[d] for r in recs) for d in DIMS}
    slices = defaultdict(lambda: defaultdict(dict))
    for r in recs:
        key = tuple(r[d] for d in fixed_dims)
        slices[key][tuple(r[s] for s in series)][r[vary]] = r
    # ties go to values in the middle of each numeric axis (n16 rather than n1)
    middling = {}
    for d in ("samples", "blur"):
        vals = sorted(freq[d])
        middling[d] = {v: abs(i - (len(vals) - 1) / 2) for i, v in enumerate(vals)}
    best, best_score = None, None
    prefer = prefer or {}
    for key, by_series in slices.items():
        fixed = dict(zip(fixed_dims, key))
        full_series = sum(1 for pts in by_series.values() if len(pts) >= need)
        if full_series == 0:
            continue
        score = (
            tuple(fixed.get(d) == v for d, v in prefer.items()),
            fixed.get("size") == (1920, 1080),
            fixed.get("stage") == "compute",
            full_series,
            sum(len(p) for p in by_series.values()),
            sum(freq[d][fixed[d]] for d in fixed_dims),
            -sum(middling[d].get(fixed[d], 0) for d in fixed_dims if d in middling),
        )
        if best_score is None or score > best_score:
            best, best_score = key, score
    if best is None:
        return None, {}
    fixed = dict(zip(fixed_dims, best))
    by_series = {s: dict(sorted(p.items())) for s, p in slices[best].items() if len(p) >= need}
    ordered = sorted(by_series.items(), key=lambda kv: series_sort_key(kv[0]))
    if len(ordered) > MAX_SERIES:
        # fixed_line says how many were left out (not a dimension: no chart reads it as one)
        fixed["left_out"] = (len(ordered) - MAX_SERIES, len(ordered))
        ordered = ordered[:MAX_SERIES]
    return fixed, dict(ordered)


def series_sort_key(key):
    kernel, api = key[0], key[1] if len(key) > 1 else ""
    return (kernel, 0 if api == "vk" else 1, api)


def kernel_colours(kernels):
    """{kernel: colour}: alchemy, hemisphere and ssdo keep theirs in every
    chart; the others take the rest in name order."""
    # matplotlib's tab10, then darker hues of tab20b: 20 distinct colours,
    # so that the kernels of a chart (at most MAX_SERIES) never share one.
    palette = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
               "#7f7f7f", "#bcbd22", "#17becf", "#393b79", "#637939", "#8c6d31", "#843c39", "#7b4173",
               "#5254a3", "#8ca252", "#bd9e39", "#ad494a", "#a55194"]
    fixed = {"alchemy": palette[0], "hemisphere": palette[1], "ssdo": palette[2]}
    rest = [c for c in palette if c not in fixed.values()]
    out = {}
    for k in sorted(kernels):
        out[k] = fixed.get(k) or rest[len([1 for v in out if v not in fixed]) % len(rest)]
    return out


class Canvas:
    """The files, the records of the last one, the output folder and what was written or skipped."""

    def __init__(self, files, outdir, title_prefix):
        matplotlib, plt = setup_matplotlib()
        from matplotlib import ticker
        matplotlib.rcParams.update({
            "svg.fonttype": "none",      # text stays text in the SVG (searchable, linkable)
            "font.size": 10,
            "axes.titlesize": 9,
            "axes.titlecolor": "#444444",
            "figure.titlesize": 13,
            "figure.titleweight": "bold",
            "legend.fontsize": 9,
            "legend.framealpha": 0.9,
            "axes.spines.top": False,
            "axes.spines.right": False,
        })
        self.plt = plt
        self.ticker = ticker
        self.files = files
        self.current = files[-1]
        self.records = list(self.current["records"].values())
        self.context = self.current["context"]
        self.outdir = outdir
        self.prefix = title_prefix
        self.written = []
        self.skipped = []
        self.kcolor = kernel_colours({r["kernel"] for f in files for r in f["records"].values()})

    # -- helpers
    def style(self, key):
        kernel, api = key
        return dict(color=self.kcolor.get(kernel, "#333333"),
                    linestyle="-" if api == "vk" else "--",
                    marker="o" if api == "vk" else "s",
                    markersize=6, linewidth=2)

    def figure(self, width=8.5, height=5.2):
        fig, ax = self.plt.subplots(figsize=(min(width, MAX_WIDTH_PX / DPI), height))
        return fig, ax

    def title(self, text):
        return f"{self.prefix}: {text}" if self.prefix else text

    def finish(self, name, fig, ax, title, subtitle_extra=None, legend=True, legend_kw=None, extra=None,
               device=True, drawn=None):
        """Title block, grid, legend, PNG + SVG and the index.json entry. drawn: the
        records the chart shows; the subtitle says their clock and what the
        whiskers are, and index.json carries both ("clock", "spread")."""
        axes = ax if isinstance(ax, (list, tuple)) else [ax]
        ax = axes[0]
        dev = device_line(self.context) if device else ""
        drawn = list(drawn) if drawn is not None else []
        clock_line = clock_text(drawn)[1] if drawn else ""
        spread_line = spread.spread_line(drawn) if drawn else ""
        sub = "\n".join(t for t in (dev, subtitle_extra, "  ·  ".join(t for t in (clock_line, spread_line) if t))
                        if t)
        # 9 pt text: about 14 characters an inch
        cols = int(fig.get_figwidth() * 14)
        sub = "\n".join(textwrap.fill(line, cols, subsequent_indent="  ") for line in sub.split("\n"))
        height = fig.get_figheight()
        fig.text(0.012, 1 - 0.10 / height, self.title(title), ha="left", va="top", fontsize=13, fontweight="bold")
        fig.text(0.012, 1 - 0.42 / height, sub, ha="left", va="top", fontsize=9, color="#444444",
                 linespacing=1.4)
        header = 0.42 + 0.19 * (sub.count("\n") + 1) + 0.04
        for a in axes:
            a.grid(True, which="major", alpha=0.35)
            a.grid(True, which="minor", alpha=0.12)
        if legend:
            handles, labels = ax.get_legend_handles_labels()
            if handles:
                kw = dict(loc="best", ncol=1 if len(handles) <= 6 else 2 if len(handles) <= LEGEND_MAX else 3)
                kw.update(legend_kw or {})
                if len(handles) > LEGEND_MAX:
                    kw.update(ncol=3, fontsize=7.5)
                ax.legend(handles, labels, **kw)
        if fig.get_figwidth() * DPI > MAX_WIDTH_PX:
            fig.set_figwidth(MAX_WIDTH_PX / DPI)
        fig.tight_layout(rect=(0, 0, 1, 1 - header / height))
        png = os.path.join(self.outdir, name + ".png")
        svg = os.path.join(self.outdir, name + ".svg")
        fig.savefig(png, dpi=DPI)
        fig.savefig(svg)
        self.plt.close(fig)
        entry = {"name": name, "title": self.title(title), "png": name + ".png", "svg": name + ".svg"}
        if drawn:
            entry["clock"] = clock_line
            entry["spread"] = spread_line
            entry["axis"] = [a.get_ylabel() for a in axes]
        entry.update(extra or {})
        self.written.append(entry)
        print(png)
        print(svg)

    def skip(self, name, why):
        self.skipped.append({"name": name, "reason": why})
        print(f"charts: note: skipped {name}: {why}", file=sys.stderr)

    def plain_log(self, axis):
        """Log axis ticks written 0.05, 0.1, 0.2, 0.5, 1 ... rather than 10^-1."""
        t = self.ticker
        axis.set_major_locator(t.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(t.FuncFormatter(lambda v, _: f"{v:g}"))
        axis.set_minor_locator(t.LogLocator(base=10, subs=(3.0, 4.0, 6.0, 7.0, 8.0, 9.0)))
        axis.set_minor_formatter(t.NullFormatter())

    def ms_axis(self, ax, values, records, log_if=40.0, what="AO pipeline time"):
        """A time axis for values (whisker ends included), labelled with the records' clock."""
        lo, hi = min(values), max(values)
        if lo > 0 and hi / lo > log_if:
            ax.set_yscale("log")
            self.plain_log(ax.yaxis)
            ax.set_ylabel(time_label(records, what, log=True))
        else:
            ax.set_ylim(0, hi * 1.12)
            ax.set_ylabel(time_label(records, what))


def paired(records, axis, a, b):
    """{series: (record at a, record at b, spread.ratio_entry(a, b))} for the
    series of the slice that varies `axis` which were measured at both values."""
    _, by_series = pick_slice(records, axis)
    out = OrderedDict()
    for key, pts in by_series.items():
        if a in pts and b in pts:
            out[key] = (pts[a], pts[b], spread.ratio_entry(pts[a], pts[b]))
    return out


def whiskers(ax, xs, ys, recs, horizontal=False, **kw):
    """Each record's spread as a whisker around (x, y), only where it has one
    (a zero-length whisker would draw its caps as if it had been measured)."""
    keep = [i for i, r in enumerate(recs) if spread.has_spread(r)]
    if not keep:
        return
    sub = [recs[i] for i in keep]
    err = {"xerr" if horizontal else "yerr": spread.errors(sub)}
    style = dict(fmt="none", ecolor="#222222", elinewidth=1.1, capsize=4, capthick=1.1, zorder=4)
    style.update(kw)
    ax.errorbar([xs[i] for i in keep], [ys[i] for i in keep], **err, **style)


def plot_series(c, ax, by_series):
    """One line per series of a slice, styled by series, with each point's
    spread as whiskers; returns the x values drawn (sorted), every value the
    axis must fit and, per series label, what was drawn at each x."""
    xs_all, ys_all, drawn = set(), [], {}
    for key, pts in by_series.items():
        xs = list(pts)
        recs = [pts[x] for x in xs]
        xs_all.update(xs)
        ys_all += spread.whisker_values(recs)
        st = c.style(key)
        ys = [r["ms"] for r in recs]
        ax.plot(xs, ys, label=series_label(key), **st)
        whiskers(ax, xs, ys, recs, ecolor=st["color"], capsize=3.5, zorder=st.get("zorder", 2.5))
        drawn[series_label(key)] = [spread_point(x, r) for x, r in zip(xs, recs)]
    return sorted(xs_all), ys_all, drawn


def spread_point(x, r):
    """A drawn point as index.json lists it."""
    x = "x".join(map(str, x)) if isinstance(x, tuple) else x
    return {"x": x, "id": r["id"], "ms": r["ms"], "q25": r.get("q25"), "q75": r.get("q75"), "n": r.get("n", 1)}


def ratio_text(entry):
    """The ratio written above a pair and the line under it: its range from
    the two spreads, or that the spreads overlap."""
    main = format_ratio(entry["ratio"])
    if entry["overlap"]:
        return main, "spreads overlap"
    if entry["low"] is not None:
        return main, f"{format_ratio(entry['low'])[:-1]}–{format_ratio(entry['high'])}"
    return main, "no spread"


def bar_pairs(c, ax, table, names, colours, edge=None):
    """Two bars per series (table as paired() returns it) with their
    whiskers; above each pair its ratio and the ratio's range, in grey when
    the two spreads overlap. Returns (every value drawn, {series label:
    ratio text}, {series label: ratio entry})."""
    keys = list(table)
    xs = list(range(len(keys)))
    w = 0.38
    vals = []
    for side, (name, colour) in enumerate(zip(names, colours)):
        recs = [table[k][side] for k in keys]
        vals += spread.whisker_values(recs)
        bx = [x + (side - 0.5) * w for x in xs]
        ax.bar(bx, [r["ms"] for r in recs], w, label=name, color=colour, edgecolor=edge, zorder=3)
        whiskers(ax, bx, [r["ms"] for r in recs], recs)
    written, entries = {}, {}
    any_spread = any(table[k][2]["low"] is not None for k in keys)
    for x, k in zip(xs, keys):
        a, b, entry = table[k]
        main, sub = ratio_text(entry)
        written[series_label(k)] = main
        entries[series_label(k)] = dict(entry, text=main, note=sub)
        top = max(r.get("q75") or r["ms"] for r in (a, b))
        grey = entry["overlap"] is True
        ax.annotate(main, (x, top), xytext=(0, 14 if any_spread else 4), textcoords="offset points", ha="center",
                    va="bottom", fontsize=10, fontweight="normal" if grey else "bold",
                    color="#888888" if grey else "black")
        if any_spread:   # with no spread anywhere the subtitle says so once
            ax.annotate(sub, (x, top), xytext=(0, 3), textcoords="offset points", ha="center", va="bottom",
                        fontsize=7.5, color="#b03030" if grey else "#555555",
                        fontstyle="italic" if grey else "normal")
    ax.set_xticks(xs)
    ax.set_xticklabels([f"{k[0]}\n{API_NAMES.get(k[1], k[1])}" for k in keys])
    return vals, written, entries
