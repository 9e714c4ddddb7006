"""compute_vs_fragment: Compute against fragment stage bars with each one's spread, the ratio (fragment / compute)
above each pair with its range, or marked where the two spreads overlap.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

from .labels import fixed_line, is_compute_card
from .plotting import bar_pairs, paired, pick_slice

NAME = "compute_vs_fragment"


def fragment_ratios(records):
    """Fragment/compute per (kernel, api) in the slice compute_vs_fragment draws:
    {(kernel, api): (compute record, fragment record, spread.ratio_entry)};
    the entry's "ratio" is fragment ms / compute ms."""
    out = paired(records, "stage", "fragment", "compute")
    return {k: (comp, frag, entry) for k, (frag, comp, entry) in out.items()}


def draw(c):
    fixed, _ = pick_slice(c.records, "stage")
    fr = fragment_ratios(c.records)
    if not fr:
        return c.skip("compute_vs_fragment", "no configuration measured in both compute and fragment stage")
    fig, ax = c.figure(width=max(6.5, 1.3 * len(fr) + 3))
    frag_label = "fragment stage"
    if is_compute_card(c.context):
        frag_label = "fragment (non-representative on H100)" if "H100" in str(c.context.get("cavity_device")) \
            else "fragment (non-representative on a compute GPU)"
    vals, labels_written, ratios = bar_pairs(c, ax, fr, ("compute stage", frag_label), ("#3b6ea8", "#e3a35a"))
    drawn = [r for k in fr for r in fr[k][:2]]
    log = max(vals) / min(vals) > 8
    c.ms_axis(ax, vals, drawn, log_if=8)
    if log:
        ax.set_ylim(min(vals) / 2, max(vals) * 4)
    else:
        ax.set_ylim(0, max(vals) * 1.3)
    ax.set_xlabel("kernel and API   (above each pair: fragment time / compute time, and its range "
                  "from the two spreads)")
    c.finish("compute_vs_fragment", fig, ax, "Compute vs fragment stage", fixed_line(fixed),
             legend_kw=dict(loc="lower left", bbox_to_anchor=(0, 1.0), ncol=2, frameon=False), drawn=drawn, extra={"labels": labels_written, "ratios": ratios})
