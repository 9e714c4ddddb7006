"""floor: measured against floor, per pass.

    charts.py floor RESULTS.json [MORE.json ...] --out DIR [--filter REGEX]

One row per pass of every configuration in `cavity run`'s results.json (or
cavity_bench JSON's `<id>@<pass>` entries): the measured median as a bar (log
scale), the pass's floor as a black tick (bench/ROOFLINE.md), measured/floor
at the end of the row; a pass without a floor is grey and says why. Writes
DIR/floor.png and DIR/floor.svg.
"""

import argparse
import importlib.util
import os
import re
import sys
import textwrap

from .inputs import BadInput, load_floor_rows
from .labels import shorten
from .plotting import DPI, setup_matplotlib


def main(argv):
    class P(argparse.ArgumentParser):
        def error(self, message):
            print(f"charts floor: {message} (usage: charts.py floor RESULTS.json [...] --out DIR)", file=sys.stderr)
            sys.exit(2)

    p = P(prog="charts floor")
    p.add_argument("results", nargs="+", metavar="RESULTS.json")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--filter", default="", metavar="REGEX", help="only configuration ids this regex finds")
    args = p.parse_args(argv)
    try:
        try:
            keep = re.compile(args.filter)
        except (re.error, RecursionError, OverflowError) as e:   # nested past what re compiles
            shown = args.filter if len(args.filter) <= 60 else args.filter[:57] + "..."
            raise BadInput(f"charts floor: --filter {shown!r}: not a regular expression ({str(e) or type(e).__name__})")
        rows = [r for path in args.results for r in load_floor_rows(path) if keep.search(r["id"])]
        if not rows:
            raise BadInput(f"charts floor: --filter {args.filter!r} matches no configuration")
        if os.path.exists(args.out) and not os.path.isdir(args.out):
            raise BadInput(f"charts floor: {args.out}: --out exists and is not a folder")
    except BadInput as e:
        print(str(e), file=sys.stderr)
        return 2
    reasons = sorted({r["reason"] for r in rows if r["floor"] is None})
    floored = [r for r in rows if r["floor"] is not None]
    if not floored:
        print(f"charts floor: note: no pass has a floor ({'; '.join(reasons)}); drawing the measured times only",
              file=sys.stderr)
    if importlib.util.find_spec("matplotlib") is None:
        print("charts floor: matplotlib is not installed (apt-get install python3-matplotlib)", file=sys.stderr)
        return 3
    os.makedirs(args.out, exist_ok=True)
    _, plt = setup_matplotlib()

    n = len(rows)
    fig, ax = plt.subplots(figsize=(11, 1.6 + 0.28 * n))
    ys = list(range(n))[::-1]   # the first pass of the first run at the top
    colour = {"fetch": "tab:blue", "dram": "tab:orange", "floor": "tab:green", "": "lightgrey"}
    positive = [r["ms"] for r in rows if r["ms"] > 0] + [r["floor"] for r in floored]
    low = min(positive) / 3 if positive else 1e-3
    for y, r in zip(ys, rows):
        ax.barh(y, max(r["ms"], low) - low, left=low, height=0.6, color=colour[r["bound"]])
        if r["floor"] is not None:
            ax.plot([r["floor"], r["floor"]], [y - 0.4, y + 0.4], color="black", lw=2)
    right = max(max(positive), low * 10) * 8 if positive else 1   # room for the ratio text
    ax.set_xscale("log")
    ax.set_xlim(low, right)
    # One reason for every pass without a floor goes in the title once, not on each row.
    for y, r in zip(ys, rows):
        end = max(r["ms"], r["floor"] or 0, low)
        text = (f"{r['ms'] / r['floor']:.2f}x floor" if r["floor"] else
                "no floor" if len(reasons) == 1 else f"no floor: {shorten(r['reason'], 60)}")
        ax.annotate(text, (end, y), textcoords="offset points", xytext=(4, -3), fontsize=7,
                    color="black" if r["floor"] else "dimgrey")
    ax.set_yticks(ys)
    ax.set_yticklabels([f"{r['id']}  {r['pass']}" for r in rows], fontsize=7)
    ax.set_xlabel("GPU time per frame, ms (log): bar = measured median, black tick = floor")
    from matplotlib.patches import Patch
    from matplotlib.lines import Line2D
    labels = {"fetch": "measured, fetch-bound floor", "dram": "measured, DRAM-bound floor",
              "floor": "measured (bound not in the benchmark JSON)", "": "measured, no floor"}
    seen = {r["bound"] for r in rows}
    handles = [Patch(color=colour[b], label=labels[b]) for b in ("fetch", "dram", "floor", "") if b in seen]
    if floored:
        handles.append(Line2D([], [], color="black", lw=2, label="floor"))
    height = fig.get_size_inches()[1]
    fig.legend(handles=handles, fontsize=7, loc="lower center", ncol=len(handles), frameon=False)
    devices = sorted({r["device"] for r in rows})
    title = "Measured against floor, per pass (bench/ROOFLINE.md)"
    sub = f"{', '.join(args.results)} · device {', '.join(devices)}"
    if not floored:
        sub += f" · no pass has a floor: {'; '.join(reasons)}"
    elif reasons:
        sub += f" · {n - len(floored)} of {n} passes have no floor"
    ax.set_title(title + "\n" + "\n".join(textwrap.wrap(sub, 130)), fontsize=9)
    ax.grid(True, axis="x", which="both", alpha=0.25)
    fig.tight_layout(rect=(0, 0.3 / height, 1, 1))   # room for the legend below the axis
    for ext in ("png", "svg"):
        path = os.path.join(args.out, "floor." + ext)
        fig.savefig(path, dpi=DPI)
        print(path)
    plt.close(fig)
    return 0
