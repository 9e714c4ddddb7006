"""quality-cost: error against the ground truth versus the AO passes' GPU time.

    charts.py quality-cost --quality Q.json [Q.json ...] --bench BENCH.json [...] --out DIR
                           [--api vk|gl] [--size WxH] [--note TEXT]

One point per AO kernel x sample count x full/half: the mean over the scenes
of each `cavity quality` row's MAE (quality.json, schema cavity.quality/1)
against the median over repetitions of pass_ao_ms plus the passes that belong
to the AO estimate (AO_COST_PASSES) of corner/<kernel>/n<N>/b4/<res>/<size>/
<api>/compute in cavity_bench JSON. The Pareto front is drawn and ringed.
Writes DIR/quality_cost.png, .svg and quality_cost.json.
"""

import argparse
import importlib.util
import json
import math
import os
import re
import sys
import textwrap
from collections import defaultdict

from .inputs import BadInput, config_id, load_pass_times, load_quality
from .labels import device_line
from .plotting import DPI, setup_matplotlib

AO_COST_PASSES = ("ao", "depth", "pyramid", "box", "downsample", "upsample")


def pareto_front(points):
    """Indices of the points no other point beats on both cost and error
    (ties on both keep the first); sorted by cost."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], math.inf
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def join_quality_cost(quality_rows, pass_times, api="vk", size=(1920, 1080), scene="corner", blur=4):
    """One point per (kernel, samples, res): mean MAE over the scenes and the
    AO cost. Returns (points, unmatched): points are dicts with kernel,
    samples, res, mae, scenes, ms, passes, id, pareto."""
    by_key = defaultdict(dict)
    for sc, kernel, n, res, mae in quality_rows:
        by_key[(kernel, n, res)][sc] = mae
    points, unmatched = [], []
    for (kernel, n, res), maes in sorted(by_key.items()):
        cid = config_id({"scene": scene, "kernel": kernel, "samples": n, "blur": blur, "res": res, "size": size,
                         "api": api, "stage": "compute"})
        passes = pass_times.get(cid)
        if not passes or "ao" not in passes:
            unmatched.append(cid)
            continue
        used = {p: passes[p] for p in AO_COST_PASSES if p in passes}
        points.append({"kernel": kernel, "samples": n, "res": res, "id": cid, "scenes": maes,
                       "mae": sum(maes.values()) / len(maes), "ms": sum(used.values()), "passes": used})
    front = set(pareto_front([(p["ms"], p["mae"]) for p in points]))
    for i, p in enumerate(points):
        p["pareto"] = i in front
    return points, unmatched


def main(argv):
    class P(argparse.ArgumentParser):
        def error(self, message):
            print(f"charts quality-cost: {message} (usage: charts.py quality-cost --quality Q.json [...] "
                  "--bench BENCH.json --out DIR)", file=sys.stderr)
            sys.exit(2)

    p = P(prog="charts quality-cost")
    p.add_argument("--quality", nargs="+", required=True, metavar="Q.json")
    p.add_argument("--bench", nargs="+", required=True, metavar="BENCH.json")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--api", default="vk", choices=("vk", "gl"))
    p.add_argument("--size", default="1920x1080", metavar="WxH")
    p.add_argument("--note", default="", metavar="TEXT", help="a line added under the title")
    args = p.parse_args(argv)
    try:
        if not re.fullmatch(r"\d+x\d+", args.size):
            raise BadInput(f"charts quality-cost: --size {args.size}: must be WxH")
        size = tuple(int(v) for v in args.size.split("x"))
        headers, rows = [], []
        for q in args.quality:
            h, r = load_quality(q)
            headers.append(h)
            rows += r
        context, times = {}, {}
        for b in args.bench:
            c, t = load_pass_times(b)
            context = context or c
            times.update(t)
        if os.path.exists(args.out) and not os.path.isdir(args.out):
            raise BadInput(f"charts: {args.out}: --out exists and is not a folder")
        points, unmatched = join_quality_cost(rows, times, args.api, size)
        if not points:
            raise BadInput("charts quality-cost: no quality row has a benchmark of the same configuration "
                           f"(e.g. {unmatched[0] if unmatched else '-'})")
    except BadInput as e:
        print(str(e), file=sys.stderr)
        return 2
    for cid in unmatched:
        print(f"charts quality-cost: note: no benchmark for {cid}; left out", file=sys.stderr)
    if importlib.util.find_spec("matplotlib") is None:
        print("charts quality-cost: matplotlib is not installed (apt-get install python3-matplotlib)", file=sys.stderr)
        return 3
    os.makedirs(args.out, exist_ok=True)
    _, plt = setup_matplotlib()

    kernels = sorted({pt["kernel"] for pt in points})
    cmap = plt.get_cmap("tab10" if len(kernels) <= 10 else "tab20")
    colour = {k: cmap(i % cmap.N) for i, k in enumerate(kernels)}
    fig, ax = plt.subplots(figsize=(10, 6.4))
    for k in kernels:
        for res, face in (("full", None), ("half", "none")):
            pts = sorted((pt for pt in points if pt["kernel"] == k and pt["res"] == res), key=lambda q: q["samples"])
            if not pts:
                continue
            xs, ys = [q["ms"] for q in pts], [q["mae"] for q in pts]
            ax.plot(xs, ys, "-" if res == "full" else ":", color=colour[k], lw=1, alpha=0.7)
            ax.scatter(xs, ys, s=36, color=colour[k], facecolors=face if face else colour[k],
                       marker="o" if res == "full" else "s", label=f"{k} ({res})", zorder=3)
            for q in pts:
                ax.annotate(f"n{q['samples']}", (q["ms"], q["mae"]), textcoords="offset points", xytext=(4, 3),
                            fontsize=6.5, color=colour[k])
    front = sorted((pt for pt in points if pt["pareto"]), key=lambda q: q["ms"])
    fx, fy = [], []
    for q in front:   # a staircase: each front point holds until the next one is better
        if fx:
            fx.append(q["ms"])
            fy.append(fy[-1])
        fx.append(q["ms"])
        fy.append(q["mae"])
    ax.plot(fx, fy, color="black", lw=1.6, zorder=2, label="Pareto front")
    ax.scatter([q["ms"] for q in front], [q["mae"] for q in front], s=140, facecolors="none", edgecolors="black",
               lw=1.3, zorder=4)
    ax.set_xscale("log")
    ax.set_xlabel("AO GPU time per frame, ms (log; ao pass + depth/pyramid/box/downsample/upsample where present)")
    ax.set_ylabel("mean |AO - ground truth| (mean over scenes)")
    device = device_line(context) if context else "unknown device"
    qh = headers[0]
    scenes = sorted({r[0] for r in rows})
    reach = qh.get("reach", "seed")
    radius = qh.get("radius")
    reach_text = f"shared reach R = {radius}" if reach == "shared" else "each seed's reach (truth at R = 0.5)"
    title = "Quality against cost: error vs ground truth against AO GPU time"
    sub = (f"time: {device}, {args.api}, {args.size}, b4, compute; quality: {qh.get('device', '?')} "
           f"{qh.get('backend', '?')} at {qh.get('width', '?')}x{qh.get('height', '?')}, {qh.get('rays', '?')} rays, "
           f"{reach_text}, scenes {', '.join(scenes)}")
    lines = textwrap.wrap(sub, 120) + (textwrap.wrap(args.note, 120) if args.note else [])
    ax.set_title(title + "\n" + "\n".join(lines), fontsize=9)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7, ncol=2, loc="upper right")
    fig.tight_layout()
    written = []
    for ext in ("png", "svg"):
        path = os.path.join(args.out, "quality_cost." + ext)
        fig.savefig(path, dpi=DPI)
        written.append(path)
    plt.close(fig)
    path = os.path.join(args.out, "quality_cost.json")
    with open(path, "w") as f:
        json.dump({"schema": "cavity.quality_cost/1", "api": args.api, "size": args.size, "device": device,
                   "quality": [{"file": q, "header": {k: v for k, v in h.items() if k != "rows"}}
                               for q, h in zip(args.quality, headers)],
                   "points": points, "unmatched": unmatched}, f, indent=2)
        f.write("\n")
    written.append(path)
    for w in written:
        print(w)
    return 0
