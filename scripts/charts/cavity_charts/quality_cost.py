"""quality-cost: error against the ground truth versus the AO pipeline's time, the screen-space Pareto front.

    charts.py quality-cost --quality Q.json [Q.json ...] --bench BENCH.json [...] --out DIR
                           [--api vk|gl] [--size WxH] [--cost pipeline|estimate] [--note TEXT]

One point per AO kernel x sample count x full/half: the mean over the scenes
of each `cavity quality` row's MAE (quality.json, schema cavity.quality/1)
against the median time of corner/<kernel>/n<N>/b4/<res>/<size>/<api>/compute
(cavity_bench JSON or results.json): the whole AO pipeline but the G-buffer,
or with --cost estimate the passes before the blur. The Pareto front is
computed over the screen-space kernels only, as `cavity quality --cost` does;
the SDF kernels, which need the scene's distance function, are drawn in grey
for reference. Writes DIR/quality_cost.png, .svg and quality_cost.json.
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

from . import spread
from .inputs import BadInput, config_id, load_quality, load_results
from .labels import clock_text, device_line
from .plotting import DPI, setup_matplotlib, whiskers

# The passes that make the AO estimate, for --cost estimate: what differs between
# kernels before the blur. The default, --cost pipeline, is the whole AO pipeline
# (every pass but the G-buffer), which is what `cavity quality --cost` ranks by,
# and the only fair cost once kernels differ in their blur (the _fast kernels'
# separable blur is most of their gain).
AO_COST_PASSES = ("ao", "depth", "pyramid", "box", "downsample", "upsample")
COSTS = ("pipeline", "estimate")
# Kernels that read the scene's distance function rather than the G-buffer: an
# engine cannot run them on its own G-buffer, so they are drawn for reference and
# left off the front (the rule of the C++ registry's kernels::evaluatesScene,
# which `cavity quality` uses for its own front).
SCENE_KERNEL = re.compile(r"^(sdf_\w+|ground_truth|gbuffer_sdf)$")


def is_screen_space(kernel):
    return not SCENE_KERNEL.match(kernel)


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


def cost_of(rec, cost):
    """spread.summary of a record's cost: its pipeline samples, or per sample
    the sum of its AO-estimate passes. None where the record lacks the ao pass."""
    passes = rec.get("passes") or {}
    if "ao" not in passes:
        return None
    if cost == "pipeline":
        st = {k: rec.get(k) for k in ("ms", "q25", "q75", "n")}
        used = {p: spread.median(v) for p, v in passes.items() if p != "gbuffer"}
        return st, used
    used = [p for p in AO_COST_PASSES if p in passes]
    n = min(len(passes[p]) for p in used)
    samples = [sum(passes[p][i] for p in used) for i in range(n)]
    return spread.summary(samples), {p: spread.median(passes[p]) for p in used}


def join_quality_cost(quality_rows, records, api="vk", size=(1920, 1080), scene="corner", blur=4, cost="pipeline"):
    """One point per (kernel, samples, res): mean MAE over the scenes and the
    cost of corner/<kernel>/n<N>/b4/<res>/<size>/<api>/compute. Returns
    (points, unmatched): points are dicts with kernel, samples, res, mae,
    scenes, ms, q25, q75, n, passes, id, clock, screen_space and pareto (on the
    front computed over the screen-space points only)."""
    by_key = defaultdict(dict)
    for sc, kernel, n, res, mae in quality_rows:
        by_key[(kernel, n, res)][sc] = mae
    points, unmatched = [], []
    for (kernel, n, res), maes in sorted(by_key.items()):
        cid = config_id({"scene": scene, "kernel": kernel, "samples": n, "blur": blur, "res": res, "size": size,
                         "api": api, "stage": "compute"})
        rec = records.get(cid)
        got = cost_of(rec, cost) if rec else None
        if not got:
            unmatched.append(cid)
            continue
        st, used = got
        points.append(dict(st, kernel=kernel, samples=n, res=res, id=cid, scenes=maes,
                           mae=sum(maes.values()) / len(maes), passes=used, clock=rec.get("clock"),
                           software=rec.get("software", False), screen_space=is_screen_space(kernel)))
    ss = [i for i, p in enumerate(points) if p["screen_space"]]
    front = {ss[j] for j in pareto_front([(points[i]["ms"], points[i]["mae"]) for i in ss])}
    for i, p in enumerate(points):
        p["pareto"] = i in front
    return points, unmatched


def place_labels(fig, ax, wanted, obstacles):
    """Writes each (text, x, y, style) of wanted, in order, at the first of a
    few offsets around its point where it overlaps no label placed before,
    no marker and stays inside the axes; a label with no room is left off.
    Returns [{"text", "box": [x0, y0, x1, y1] in pixels}] placed and the
    texts left off."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    taken = list(obstacles)
    placed, left_off = [], []
    offsets = [(5, 3), (5, -11), (-5, 3), (-5, -11), (0, 8), (0, -14), (9, -4), (-9, -4),
               (12, 10), (12, -18), (-12, 10), (-12, -18)]
    for text, x, y, style in wanted:
        done = False
        for dx, dy in offsets:
            ha = "left" if dx > 0 else "right" if dx < 0 else "center"
            ann = ax.annotate(text, (x, y), xytext=(dx, dy), textcoords="offset points", ha=ha, va="bottom",
                              **style)
            box = ann.get_window_extent(renderer).expanded(1.04, 1.1)
            inside = box.x0 >= frame.x0 and box.x1 <= frame.x1 and box.y0 >= frame.y0 and box.y1 <= frame.y1
            if inside and not any(box.overlaps(t) for t in taken):
                taken.append(box)
                placed.append({"text": text, "box": [box.x0, box.y0, box.x1, box.y1]})
                done = True
                break
            ann.remove()
        if not done:
            left_off.append(text)
    return placed, left_off


def check_headers(paths, headers):
    """Quality files charted together must measure the same thing: one reach,
    radius and blur (a kernel after a blur against one without is no ranking)."""
    for key in ("reach", "radius", "blur"):
        values = {json.dumps(h.get(key)) for h in headers}
        if len(values) > 1:
            listed = ", ".join(f"{p}: {h.get(key)}" for p, h in zip(paths, headers))
            raise BadInput(f"charts quality-cost: the --quality files differ in {key} ({listed}); "
                           f"chart files of one {key} together")


def main(argv):
    class P(argparse.ArgumentParser):
        def error(self, message):
            print(f"charts quality-cost: {message} (usage: charts.py quality-cost --quality Q.json [...] "
                  "--bench BENCH.json --out DIR)", file=sys.stderr)
            sys.exit(2)

    p = P(prog="charts quality-cost")
    p.add_argument("--quality", nargs="+", required=True, metavar="Q.json")
    p.add_argument("--bench", nargs="+", required=True, metavar="BENCH.json",
                   help="cavity_bench JSON or cavity run's results.json")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--api", default="vk", choices=("vk", "gl"))
    p.add_argument("--size", default="1920x1080", metavar="WxH")
    p.add_argument("--cost", default="pipeline", choices=COSTS,
                   help="pipeline: every pass but the G-buffer (default, as cavity quality --cost); "
                        "estimate: the passes before the blur (" + ", ".join(AO_COST_PASSES) + ")")
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
        check_headers(args.quality, headers)
        context, records = {}, {}
        for b in args.bench:
            f = load_results(b)
            context = context or f["context"]
            records.update(f["records"])
        if os.path.exists(args.out) and not os.path.isdir(args.out):
            raise BadInput(f"charts: {args.out}: --out exists and is not a folder")
        points, unmatched = join_quality_cost(rows, records, args.api, size, cost=args.cost)
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
    placed, left_off = draw(plt, args, points, headers, rows, context)
    if left_off:
        print(f"charts quality-cost: note: {len(left_off)} point label(s) had no room and were left off "
              f"(e.g. {left_off[0]}); quality_cost.json has every point", file=sys.stderr)
    written = []
    for ext in ("png", "svg"):
        path = os.path.join(args.out, "quality_cost." + ext)
        plt.gcf().savefig(path, dpi=DPI)
        written.append(path)
    plt.close("all")
    path = os.path.join(args.out, "quality_cost.json")
    with open(path, "w") as f:
        json.dump({"schema": "cavity.quality_cost/1", "api": args.api, "size": args.size, "cost": args.cost,
                   "device": device_line(context) if context else "unknown device",
                   "clock": clock_text(points)[1], "spread": spread.spread_line(points),
                   "front": [p["id"] for p in sorted(points, key=lambda q: q["ms"]) if p["pareto"]],
                   "quality": [{"file": q, "header": {k: v for k, v in h.items() if k != "rows"}}
                               for q, h in zip(args.quality, headers)],
                   "points": points, "unmatched": unmatched, "labels": placed, "labels_left_off": left_off},
                  f, indent=2)
        f.write("\n")
    written.append(path)
    for w in written:
        print(w)
    return 0


SDF_MARKERS = ("x", "+", "1", "2", "3", "4", "*", "|")


def front_table(front):
    """The front as the chart lists it beside the axes: one numbered line per point."""
    lines = []
    for i, q in enumerate(front, 1):
        spread_text = f" ({q['q25']:.3g}–{q['q75']:.3g})" if spread.has_spread(q) else ""
        wall = " [wall clock]" if q.get("clock") == "wall" else ""
        lines.append(f"{i:>2}  {q['kernel']} n{q['samples']} {q['res']}: {q['ms']:.3g} ms{spread_text}, "
                     f"MAE {q['mae']:.4f}{wall}")
    return lines


def draw(plt, args, points, headers, rows, context):
    """The chart on pyplot's current figure; returns place_labels' result."""
    from matplotlib import ticker
    from matplotlib.lines import Line2D
    from matplotlib.transforms import Bbox
    screen = sorted({pt["kernel"] for pt in points if pt["screen_space"]})
    scene = sorted({pt["kernel"] for pt in points if not pt["screen_space"]})
    cmap = plt.get_cmap("tab10" if len(screen) <= 10 else "tab20")
    colour = {k: cmap(i % cmap.N) for i, k in enumerate(screen)}
    colour.update({k: "#8a8a8a" for k in scene})
    marker = {k: SDF_MARKERS[i % len(SDF_MARKERS)] for i, k in enumerate(scene)}
    fig = plt.figure(figsize=(12.5, 7.6))
    ax = fig.add_axes((0.07, 0.1, 0.58, 0.70))
    handles = []
    xy = []
    for k in screen + scene:
        ss = k in screen
        for res in ("full", "half"):
            pts = sorted((pt for pt in points if pt["kernel"] == k and pt["res"] == res), key=lambda q: q["samples"])
            if not pts:
                continue
            xs, ys = [q["ms"] for q in pts], [q["mae"] for q in pts]
            xy += list(zip(xs, ys))
            line = "-" if res == "full" else ":"
            if ss:
                ax.plot(xs, ys, line, color=colour[k], lw=1.1, alpha=0.75, zorder=2)
                whiskers(ax, xs, ys, pts, horizontal=True, ecolor=colour[k], elinewidth=0.9, capsize=2, alpha=0.8,
                         zorder=2.5)
                ax.scatter(xs, ys, s=38, color=colour[k], facecolors=colour[k] if res == "full" else "white",
                           marker="o" if res == "full" else "s", linewidths=1.3, zorder=3)
            else:
                ax.plot(xs, ys, line, color=colour[k], lw=0.7, alpha=0.45, zorder=1)
                ax.scatter(xs, ys, s=30, color=colour[k], marker=marker[k], linewidths=1.0, alpha=0.9, zorder=1.5)
        handles.append(Line2D([], [], color=colour[k], marker="o" if ss else marker[k], lw=1.1 if ss else 0.7,
                              label=k if ss else f"{k} (SDF)"))
    handles += [Line2D([], [], color="#555555", marker="o", lw=1.1, label="full resolution (filled, solid)"),
                Line2D([], [], color="#555555", marker="s", markerfacecolor="white", ls=":", lw=1.1,
                       label="half resolution (open, dotted)")]
    front = sorted((pt for pt in points if pt["pareto"]), key=lambda q: q["ms"])
    fx, fy = [], []
    for q in front:   # a staircase: each front point holds until the next one is better
        if fx:
            fx.append(q["ms"])
            fy.append(fy[-1])
        fx.append(q["ms"])
        fy.append(q["mae"])
    ax.plot(fx, fy, color="black", lw=1.6, zorder=2.2)
    ax.scatter([q["ms"] for q in front], [q["mae"] for q in front], s=150, facecolors="none", edgecolors="black",
               lw=1.3, zorder=4)
    handles.append(Line2D([], [], color="black", lw=1.6, marker="o", markerfacecolor="none", markersize=11,
                          label="Pareto front, screen-space kernels only"))
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(ticker.NullFormatter())
    clock, clock_line = clock_text(points)
    what = ("AO pipeline time per frame (every pass but the G-buffer)" if args.cost == "pipeline" else
            "AO estimate time per frame (" + "/".join(AO_COST_PASSES) + " where present; blur and composite left out)")
    ax.set_xlabel(f"{what}, ms, log scale\n{clock}")
    ax.set_ylabel("mean |AO - ground truth| (mean over scenes)")
    ax.grid(True, which="both", alpha=0.25)
    device = device_line(context) if context else "unknown device"
    qh = headers[0]
    scenes = sorted({r[0] for r in rows})
    reach = qh.get("reach", "seed")
    radius = qh.get("radius")
    reach_text = f"shared reach R = {radius}" if reach == "shared" else "each seed's reach (truth at R = 0.5)"
    blur = qh.get("blur")
    blur_text = f"AO after a blur of radius {blur}" if blur else "raw AO (before the blur)"
    sub = (f"time: {device}, {args.api}, {args.size}, b4, compute  ·  quality: {qh.get('device', '?')} "
           f"{qh.get('backend', '?')} at {qh.get('width', '?')}x{qh.get('height', '?')}, {qh.get('rays', '?')} rays, "
           f"{reach_text}, {blur_text}, scenes {', '.join(scenes)}")
    what_line = ("The front is computed over the screen-space kernels (what an engine can run on its own "
                 "G-buffer), as `cavity quality --cost` does; the grey SDF kernels need the scene's distance "
                 "function and are drawn for reference only. Labels: samples per pixel; numbers: the front, listed "
                 "on the right.")
    lines = (textwrap.wrap(sub, 165) + textwrap.wrap(what_line, 165)
             + textwrap.wrap(f"{clock_line}  ·  cost {spread.spread_line(points)}", 165)
             + (textwrap.wrap(args.note, 165) if args.note else []))
    fig.text(0.012, 0.985, "Quality against cost: error against the ground truth vs AO time", ha="left", va="top",
             fontsize=13, fontweight="bold")
    fig.text(0.012, 0.945, "\n".join(lines), ha="left", va="top", fontsize=8.5, color="#444444", linespacing=1.4)
    leg = ax.legend(handles=handles, fontsize=7.5, loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False,
                    ncol=2 if len(handles) > 14 else 1)
    table = "Pareto front (fastest first; ms: median (IQR))\n" + "\n".join(front_table(front))
    fig.canvas.draw()
    leg_box = leg.get_window_extent(fig.canvas.get_renderer()).transformed(fig.transFigure.inverted())
    fig.text(0.67, min(leg_box.y0 - 0.03, 0.6), table, ha="left", va="top", fontsize=7.5, family="monospace",
             linespacing=1.35)
    # labels: the front's numbers first, then every other screen-space point's sample count
    obstacles = []
    for x, y in xy:
        px, py = ax.transData.transform((x, y))
        obstacles.append(Bbox([[px - 5, py - 5], [px + 5, py + 5]]))
    wanted = [(str(i), q["ms"], q["mae"], dict(fontsize=8, fontweight="bold", color="black"))
              for i, q in enumerate(front, 1)]
    wanted += [(f"n{q['samples']}", q["ms"], q["mae"], dict(fontsize=6.5, color=colour[q["kernel"]]))
               for q in sorted(points, key=lambda q: (q["kernel"], q["res"], q["samples"]))
               if q["screen_space"] and not q["pareto"]]
    return place_labels(fig, ax, wanted, obstacles)
