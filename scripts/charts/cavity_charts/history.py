"""history: The time of each configuration across the files given, in the order given
(needs two or more files): the configurations whose time changed most.

draw(c) draws it on a plotting.Canvas (or says on stderr why it is skipped).
"""

import math
import re

from . import spread
from .plotting import whiskers
from .labels import device_line, device_name, driver_name, file_label, short_ids, shorten

HISTORY_MAX_LINES = 8

NAME = "history"


def history_series(files, limit=HISTORY_MAX_LINES):
    """Configurations present in every file: (ids chosen, {id: [ms per file]}, n common).
    At most `limit`, those whose time changed most between the first and last
    file first."""
    common = [cid for cid in files[-1]["records"] if all(cid in f["records"] for f in files)]
    values = {cid: [f["records"][cid]["ms"] for f in files] for cid in common}
    order = sorted(common, key=lambda c: (-abs(math.log(values[c][-1] / values[c][0])), c))
    chosen = sorted(order[:limit], key=lambda c: -abs(values[c][-1] / values[c][0] - 1))
    return chosen, values, len(common)


def draw(c):
    if len(c.files) < 2:
        return c.skip("history", "needs two or more result files")
    chosen, values, n_common = history_series(c.files)
    if not chosen:
        return c.skip("history", "no configuration is in every file")
    fig, (ax, ax2) = c.plt.subplots(1, 2, figsize=(13, 5.8), sharex=True)
    xs = list(range(len(c.files)))
    common, short = short_ids(chosen) if len(chosen) > 1 else ("", {chosen[0]: chosen[0]})
    cmap = c.plt.get_cmap("tab10")
    all_v, all_rel, drawn = [], [], []
    for i, cid in enumerate(chosen):
        v = values[cid]
        rel = [(x / v[0] - 1) * 100 for x in v]
        all_v += v
        all_rel += rel
        st = dict(marker="o", linewidth=1.8, color=cmap(i % 10))
        recs = [f["records"][cid] for f in c.files]
        drawn += recs
        all_v += spread.whisker_values(recs)
        ax.plot(xs, v, label=f"{short[cid]}  {v[0]:.3g} → {v[-1]:.3g} ms  ({rel[-1]:+.1f}%)", **st)
        whiskers(ax, xs, v, recs, ecolor=st["color"], capsize=3)
        ax2.plot(xs, rel, **st)
    devices = {device_name(f["context"]) for f in c.files}
    drivers = {driver_name(f["context"]) for f in c.files}
    width = max(12, 110 // len(c.files))
    labels = []
    for f in c.files:
        lab = file_label(f, width)
        if len(devices) > 1:
            lab += "\n" + shorten(device_name(f["context"]), width)
        if len(drivers) > 1:
            # "gl: 550.54.15; vk: 550.54.15.0": the first API's is enough to tell runs apart
            drv = (driver_name(f["context"]) or "?").split(";")[0]
            lab += "\ndriver " + shorten(re.sub(r"^(gl|vk)\s*:\s*", "", drv), width - 7)
        labels.append(lab)
    for a in (ax, ax2):
        a.set_xticks(xs)
        a.set_xticklabels(labels, fontsize=8)
        a.tick_params(axis="x", labelbottom=True)
        a.set_xlim(-0.25, len(xs) - 0.75)
        a.set_xlabel("result file, in the order given")
    c.ms_axis(ax, all_v, drawn, log_if=8.0)
    ax.set_title("median time, whiskers: spread", loc="left", fontsize=9)
    ax2.axhline(0, color="#555555", linewidth=1)
    ax2.axhspan(-10, 10, color="#999999", alpha=0.15, label="±10%")
    span = max(12.0, max(abs(r) for r in all_rel) * 1.15)
    ax2.set_ylim(-span, span)
    ax2.set_ylabel("change vs first file (%)")
    ax2.set_title("change vs first file (shaded: ±10%; below 0: faster)", loc="left", fontsize=9)
    what = (f"all {n_common} configurations present in every file" if len(chosen) == n_common else
            f"the {len(chosen)} of {n_common} configurations present in every file that changed most")
    sub = what + (f"  ·  all: {common}" if common else "")
    handles, labels = ax.get_legend_handles_labels()
    ax2.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, title_fontsize=8,
               title="configuration: first → last file (change)")
    if len(devices) > 1 or len(drivers) > 1:
        what_differs = "devices" if len(devices) > 1 else "drivers"
        sub = f"latest: {device_line(c.context)}  ({what_differs} differ: see x axis)\n{sub}"
    c.finish("history", fig, [ax, ax2], "AO time across runs", sub, legend=False, device=False, drawn=drawn)
