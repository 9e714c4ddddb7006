"""compute_vs_fragment: Compute against fragment stage bars, the ratio (fragment / compute) above each pair.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from collections import OrderedDict

from .labels import API_NAMES, fixed_line, format_ratio, is_compute_card, series_label
from .plotting import pick_slice

NAME = "compute_vs_fragment"


def fragment_ratios(records):
    """Fragment/compute time per (kernel, api) in the slice compute_vs_fragment draws."""
    fixed, by_series = pick_slice(records, "stage")
    out = OrderedDict()
    for key, pts in by_series.items():
        if "compute" in pts and "fragment" in pts:
            c, f = pts["compute"]["ms"], pts["fragment"]["ms"]
            out[key] = (c, f, f / c)
    return out


def draw(c):
    fixed, _ = pick_slice(c.records, "stage")
    fr = fragment_ratios(c.records)
    if not fr:
        return c.skip("compute_vs_fragment", "no configuration measured in both compute and fragment stage")
    fig, ax = c.figure(width=max(6.5, 1.3 * len(fr) + 3))
    keys = list(fr)
    xs = list(range(len(keys)))
    w = 0.38
    comp = [fr[k][0] for k in keys]
    frag = [fr[k][1] for k in keys]
    frag_label = "fragment stage"
    if is_compute_card(c.context):
        frag_label = "fragment (non-representative on H100)" if "H100" in str(c.context.get("cavity_device")) \
            else "fragment (non-representative on a compute GPU)"
    ax.bar([x - w / 2 for x in xs], comp, w, label="compute stage", color="#3b6ea8", zorder=3)
    ax.bar([x + w / 2 for x in xs], frag, w, label=frag_label, color="#e3a35a", zorder=3)
    labels_written = {}
    for x, k in zip(xs, keys):
        text = format_ratio(fr[k][2])
        labels_written[series_label(k)] = text
        ax.annotate(text, (x, max(fr[k][0], fr[k][1])), xytext=(0, 4), textcoords="offset points",
                    ha="center", va="bottom", fontsize=10, fontweight="bold")
    ax.set_xticks(xs)
    ax.set_xticklabels([f"{k[0]}\n{API_NAMES.get(k[1], k[1])}" for k in keys])
    vals = comp + frag
    if max(vals) / min(vals) > 8:
        ax.set_yscale("log")
        c.plain_log(ax.yaxis)
        ax.set_ylim(min(vals) / 2, max(vals) * 3)
        ax.set_ylabel("GPU time (ms, log scale)")
    else:
        ax.set_ylim(0, max(vals) * 1.22)
        ax.set_ylabel("GPU time (ms)")
    ax.set_xlabel("kernel and API   (number above each pair: fragment time / compute time)")
    c.finish("compute_vs_fragment", fig, ax, "Compute vs fragment stage", fixed_line(fixed),
             legend_kw=dict(loc="upper left"), extra={"labels": labels_written})
