"""passes: Where each kernel's AO time goes, pass by pass: a stacked bar per kernel and API, each pass's spread as
a whisker at its segment's end, the pipeline's median and spread at the bar's end.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
Reads cavity_bench's pass_<name>_ms counters (one value per repetition) or a
results.json's passes[].samples_ms (one per frame).
"""

from . import spread
from .inputs import ENGINE_PASSES
from .labels import API_NAMES, fixed_line, time_label
from .plotting import pick_slice, whiskers

NAME = "passes"

# Passes in the order a frame runs them, so that a bar reads left to right as
# the GPU does; a pass not listed goes after these, by name.
ORDER = ("depth", "pyramid", "downsample", "ao", "box", "upsample", "indirect", "blur", "blur_x", "blur_y",
         "indirect_blur", "indirect_blur_x", "indirect_blur_y", "composite")
COLOURS = ("#1f77b4", "#aec7e8", "#ff7f0e", "#2ca02c", "#98df8a", "#d62728", "#9467bd", "#c5b0d5",
           "#8c564b", "#c49c94", "#e377c2", "#f7b6d2", "#bcbd22", "#17becf", "#9edae5", "#7f7f7f")


def pass_order(names):
    known = [n for n in ORDER if n in names]
    return known + sorted(n for n in names if n not in ORDER)


def pass_table(records):
    """The rows the chart draws: the slice where kernel and API vary and every
    other axis is fixed (as the other charts pick it), fastest pipeline first.
    Returns (fixed, [{"id", "kernel", "api", "record", "passes": {pass:
    spread.summary}}], the passes drawn in order, the engine passes left out)."""
    recs = [r for r in records if r.get("passes")]
    fixed, by_series = pick_slice(recs, "kernel", series=("api",), need=1)
    if not by_series:
        return None, [], [], []
    rows, names, engine = [], set(), set()
    for (api,), pts in by_series.items():
        for kernel, r in pts.items():
            drawn = {p: spread.summary(v) for p, v in r["passes"].items() if p not in ENGINE_PASSES}
            engine.update(p for p in r["passes"] if p in ENGINE_PASSES)
            names.update(drawn)
            rows.append({"id": r["id"], "kernel": kernel, "api": api, "record": r, "passes": drawn})
    rows.sort(key=lambda row: (row["record"]["ms"], row["kernel"], row["api"]))
    return fixed, rows, pass_order(names), sorted(engine)


def draw(c):
    fixed, rows, names, engine = pass_table(c.records)
    if not rows:
        return c.skip(NAME, "no configuration has per-pass times (pass_<name>_ms counters or passes[].samples_ms)")
    colour = {n: COLOURS[i % len(COLOURS)] for i, n in enumerate(names)}
    fig, ax = c.figure(width=11, height=max(3.6, 1.9 + 0.42 * len(rows)))
    ys = list(range(len(rows)))[::-1]   # the fastest at the top
    right = 0.0
    for y, row in zip(ys, rows):
        left = end = 0.0
        for n in names:
            st = row["passes"].get(n)
            if st is None:
                continue
            ax.barh(y, st["ms"], left=left, height=0.62, color=colour[n], edgecolor="white", linewidth=0.5,
                    zorder=3)
            # the pass's interquartile range, drawn where its segment ends
            whiskers(ax, [left + st["ms"]], [y], [st], horizontal=True, elinewidth=1.0, capsize=2.5)
            left += st["ms"]
            if spread.has_spread(st):
                end = max(end, left + st["q75"] - st["ms"])
        rec = row["record"]
        end = max(end, left)
        text = f"pipeline {rec['ms']:.3g} ms"
        if spread.has_spread(rec):
            text += f" (IQR {rec['q25']:.4g}–{rec['q75']:.4g})"
        ax.annotate(text, (end, y), xytext=(6, 0), textcoords="offset points", va="center", fontsize=8)
        right = max(right, end)
    ax.set_yticks(ys)
    ax.set_yticklabels([f"{row['kernel']} · {API_NAMES.get(row['api'], row['api'])}" for row in rows], fontsize=9)
    ax.set_xlim(0, right * 1.4)
    drawn = [row["record"] for row in rows]
    ax.set_xlabel(time_label(drawn, "time per frame, each pass's median stacked").replace("\n", ";  "))
    from matplotlib.patches import Patch
    handles = [Patch(color=colour[n], label=n) for n in names]
    ax.legend(handles=handles, loc="lower left", bbox_to_anchor=(0, 1.0), fontsize=8, ncol=min(len(names), 8),
              frameon=False, title="passes, in the order a frame runs them", title_fontsize=8, alignment="left")
    note = ("whisker at each segment's end: that pass's spread; text: the whole pipeline's median and spread "
            "(the passes' medians need not add up to it)"
            + (f"; left out: {', '.join(engine)} (the engine's own pass)" if engine else ""))
    table = [{"id": row["id"], "ms": row["record"]["ms"], "q25": row["record"].get("q25"),
              "q75": row["record"].get("q75"), "n": row["record"].get("n", 1), "passes": row["passes"]}
             for row in rows]
    c.finish(NAME, fig, ax, "Where the AO time goes, pass by pass", fixed_line(fixed) + "\n" + note,
             legend=False, drawn=drawn, extra={"rows": table, "pass_order": names, "left_out": engine})
