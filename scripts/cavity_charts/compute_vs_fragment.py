"""compute_vs_fragment: Compute against fragment stage bars, the ratio (fragment / compute) above each pair.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line, is_compute_card
from .plotting import label_pairs, paired, pick_slice

NAME = "compute_vs_fragment"


def fragment_ratios(records):
    """Fragment/compute time per (kernel, api) in the slice compute_vs_fragment draws."""
    return paired(records, "stage", "compute", "fragment", lambda compute, fragment: fragment / compute)


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
    labels_written = label_pairs(ax, fr)
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
