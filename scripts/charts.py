#!/usr/bin/env python3
"""Charts from cavity_bench results (Google Benchmark JSON).

    python3 scripts/charts.py RESULT.json [MORE.json ...] --out DIR [--title TEXT]

Writes DIR/<chart>.png (150 dpi) and DIR/<chart>.svg for every chart the data
has an axis for, DIR/index.json listing them (name, title, png, svg), and
prints the path of each file written. Charts 1-6 use the LAST file given; with
two or more files, the history chart follows each configuration across all of
them in the order given.

  time_vs_samples      GPU time against AO samples per pixel, a line per (kernel, API)
  time_vs_blur         GPU time against bilateral blur radius
  full_vs_half         full vs half resolution bars, speed-up (full/half) above each pair
  time_vs_megapixels   GPU time against image size, with a linear fit through the origin
  gl_vs_vk             OpenGL time against Vulkan time for the same configuration
  compute_vs_fragment  compute vs fragment stage bars, ratio above each pair
  history              time of each configuration across the files given

Each chart fixes every other configuration axis at one value (preferring
1920x1080 and the compute stage, then the slice with the most points) and says
which in its subtitle. A chart whose axis the data lacks is skipped with a note
on stderr.

Input: the JSON cavity_bench writes with --benchmark_format=json or
--benchmark_out. Benchmark names are configuration ids,
    <scene>/<kernel>/n<samples>/b<blur>/<full|half>/<W>x<H>/<gl|vk>/<compute|fragment>
to which Google Benchmark appends "/iterations:N", "/manual_time" and, for
aggregates, "_median" etc. The time charted is real_time (the manual GPU time
of the AO part of the pipeline), in ms; the "median" aggregate is used where
repetitions were run, else the mean of the iteration entries.

Exit codes: 0 written; 2 bad usage or input (one line on stderr names the file
and what is wrong; nothing is written); 3 matplotlib is missing.

Subcommand: quality against cost

    python3 scripts/charts.py quality-cost --quality Q.json [Q.json ...] --bench BENCH.json [...] --out DIR
                              [--api vk|gl] [--size WxH] [--note TEXT]

plots each AO kernel x sample count x full/half as one point: the error
against the ground truth (mean over the scenes of each `cavity quality`
row's MAE; quality.json, schema cavity-quality/1, one file per resolution)
against the AO passes' GPU time from cavity_bench JSON (the median over
repetitions of pass_ao_ms plus the passes that belong to the AO estimate:
depth, pyramid, box, downsample, upsample; the bilateral blur and composite are the
same for every kernel and left out) of corner/<kernel>/n<N>/b4/<res>/<size>/
<api>/compute. The Pareto front (no other point both faster and closer to
the truth) is drawn and its points ringed. Writes DIR/quality_cost.png,
.svg and quality_cost.json (the joined points, front marked). A quality row
with no benchmark (or the reverse) is listed on stderr and left out.

Subcommand: measured against floor

    python3 scripts/charts.py floor RESULTS.json [MORE.json ...] --out DIR [--filter REGEX]

reads `cavity run`'s results.json (schema cavity.results/1), or cavity_bench's
JSON (each `<id>@<pass>` entry's median over the repetitions), and draws, one row
per pass of every configuration, the measured median (a bar, log scale) and
the pass's floor (a black tick; bench/ROOFLINE.md), with measured/floor at the
end of the row. A pass with no floor (a software renderer, a device not in
the floor table, no cost declared) has its bar in grey and its reason at the
end of the row; a file with no floor at all says so on stderr and in the
title, and draws the measured times. Writes DIR/floor.png, DIR/floor.svg.

Uses only the Python standard library and matplotlib (Debian's python3-matplotlib).
"""

import argparse
import importlib.util
import json
import math
import os
import re
import statistics
import sys
import textwrap
from collections import Counter, OrderedDict, defaultdict

DPI = 150
CHART_NAMES = ("time_vs_samples", "time_vs_blur", "full_vs_half", "time_vs_megapixels",
               "gl_vs_vk", "compute_vs_fragment", "history")
DIMS = ("scene", "kernel", "samples", "blur", "res", "size", "api", "stage")
API_NAMES = {"gl": "OpenGL", "vk": "Vulkan"}
TIME_UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}
HISTORY_MAX_LINES = 8
LEGEND_MAX = 12


class BadInput(Exception):
    """Input that is not usable; the message is the one line printed."""


# --------------------------------------------------------------------------
# Parsing

ID_RE = re.compile(r"^(?P<scene>[^/]+)/(?P<kernel>[^/]+)/n(?P<samples>\d+)/b(?P<blur>\d+)/"
                   r"(?P<res>full|half)/(?P<w>\d+)x(?P<h>\d+)/(?P<api>gl|vk)/(?P<stage>compute|fragment)$")
# Google Benchmark's own name parts: /iterations:50, /repeats:3, /threads:1,
# /min_time:..., /min_warmup_time:..., /manual_time, /real_time.
GB_PART_RE = re.compile(r"/(?:manual_time|real_time|process_time|(?:iterations|repeats|threads|min_time|"
                        r"min_warmup_time):[^/]*)$")
AGG_RE = re.compile(r"_(?:mean|median|stddev|cv|BigO|RMS)$")


def strip_name(name, aggregate_name=None):
    """The configuration-id part of a Google Benchmark name: drops an aggregate
    suffix ("_median"), then "/manual_time", "/iterations:N" and the like."""
    s = name
    if aggregate_name and s.endswith("_" + aggregate_name):
        s = s[: -len(aggregate_name) - 1]
    else:
        m = AGG_RE.search(s)
        if m:
            s = s[: m.start()]
    while True:
        m = GB_PART_RE.search(s)
        if not m:
            return s
        s = s[: m.start()]


def parse_id(name, counters=None, aggregate_name=None):
    """Configuration of a benchmark name, as a dict with the keys of DIMS
    (size is (W, H)), or None. Where the name is not a configuration id,
    whatever the counters (samples, blur, half, fragment, width, height)
    and recognisable name parts give is used; scene, kernel and API must
    come from the name."""
    s = strip_name(name, aggregate_name)
    m = ID_RE.match(s)
    if m:
        return {"scene": m["scene"], "kernel": m["kernel"], "samples": int(m["samples"]),
                "blur": int(m["blur"]), "res": m["res"], "size": (int(m["w"]), int(m["h"])),
                "api": m["api"], "stage": m["stage"]}
    counters = counters or {}
    parts = [p for p in s.split("/") if p]
    cfg = {}
    rest = []
    for p in parts:
        if re.fullmatch(r"n\d+", p): cfg["samples"] = int(p[1:])
        elif re.fullmatch(r"b\d+", p): cfg["blur"] = int(p[1:])
        elif p in ("full", "half"): cfg["res"] = p
        elif re.fullmatch(r"\d+x\d+", p): cfg["size"] = tuple(int(v) for v in p.split("x"))
        elif p in ("gl", "vk"): cfg["api"] = p
        elif p in ("compute", "fragment"): cfg["stage"] = p
        else: rest.append(p)

    def num(key):
        v = counters.get(key)
        return v if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) else None

    if "samples" not in cfg and num("samples") is not None: cfg["samples"] = int(num("samples"))
    if "blur" not in cfg and num("blur") is not None: cfg["blur"] = int(num("blur"))
    if "res" not in cfg and num("half") is not None: cfg["res"] = "half" if num("half") else "full"
    if "stage" not in cfg and num("fragment") is not None: cfg["stage"] = "fragment" if num("fragment") else "compute"
    if "size" not in cfg and num("width") is not None and num("height") is not None:
        cfg["size"] = (int(num("width")), int(num("height")))
    if len(rest) >= 2:
        cfg.setdefault("scene", rest[0])
        cfg.setdefault("kernel", rest[1])
    if all(k in cfg for k in DIMS):
        return cfg
    return None


def config_id(cfg):
    w, h = cfg["size"]
    return (f"{cfg['scene']}/{cfg['kernel']}/n{cfg['samples']}/b{cfg['blur']}/{cfg['res']}/"
            f"{w}x{h}/{cfg['api']}/{cfg['stage']}")


def _is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def load_results(path):
    """Reads and checks one Google Benchmark JSON file. Returns
    {"path", "name", "date", "context", "records": {id: record}, "dropped"};
    a record is the configuration (DIMS) plus "id", "ms" and "wall". Raises BadInput
    with the one-line message (naming the file) when it is not usable."""
    shown = path

    def bad(what):
        return BadInput(f"charts: {shown}: {what}")

    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise bad(f"cannot read ({e.strerror or e})")
    try:
        data = json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise bad("not JSON (not UTF-8 text)")
    except json.JSONDecodeError as e:
        raise bad(f"not JSON ({e.msg} at line {e.lineno} column {e.colno})")
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        raise bad("not Google Benchmark JSON (no 'benchmarks' list)")
    context = data.get("context")
    if context is not None and not isinstance(context, dict):
        raise bad("not Google Benchmark JSON ('context' is not an object)")
    context = context or {}
    groups = defaultdict(lambda: {"median": [], "mean": [], "iteration": [], "cfg": None, "wall": False})
    for i, e in enumerate(data["benchmarks"]):
        if not isinstance(e, dict):
            raise bad(f"not Google Benchmark JSON (benchmarks[{i}] is not an object)")
        if not isinstance(e.get("name"), str) or not e["name"]:
            raise bad(f"not Google Benchmark JSON (benchmarks[{i}] has no 'name')")
        if e.get("error_occurred") or e.get("skipped") not in (None, False, 0):
            continue  # a benchmark that skipped itself with an error has no time to chart
        agg = e.get("aggregate_name")
        if e.get("run_type") == "aggregate" and agg not in ("mean", "median"):
            continue  # stddev, cv, BigO, RMS: not a time
        if not _is_number(e.get("real_time")):
            raise bad(f"not Google Benchmark JSON (benchmarks[{i}] '{e['name']}' has no numeric 'real_time')")
        unit = e.get("time_unit", "ns")
        if unit not in TIME_UNIT_MS:
            raise bad(f"benchmarks[{i}] '{e['name']}': unknown time_unit '{unit}' (ns, us, ms or s)")
        cfg = parse_id(e["name"], e, agg if e.get("run_type") == "aggregate" else None)
        if cfg is None:
            continue
        g = groups[config_id(cfg)]
        g["cfg"] = cfg
        kind = agg if e.get("run_type") == "aggregate" else "iteration"
        g[kind].append(e["real_time"] * TIME_UNIT_MS[unit])
        if isinstance(e.get("label"), str) and "clock=wall" in e["label"]:
            g["wall"] = True
    if not groups:
        n = len(data["benchmarks"])
        raise bad(f"no usable benchmark entries (none of its {n} is named by a Cavity configuration id "
                  "and has a time)" if n else "no benchmark entries ('benchmarks' is empty)")
    records = OrderedDict()
    dropped = []
    for cid, g in groups.items():
        for kind in ("median", "mean", "iteration"):
            if g[kind]:
                ms = sum(g[kind]) / len(g[kind])
                break
        if ms > 0:
            records[cid] = dict(g["cfg"], id=cid, ms=ms, wall=g["wall"])
        else:
            dropped.append(cid)  # a zero time is a timer that did not run; it has no ratio or log
    if not records:
        raise bad("no usable benchmark entries (every time is zero)")
    date = context.get("date") if isinstance(context.get("date"), str) else None
    return {"path": path, "name": os.path.basename(path), "date": date, "context": context, "records": records,
            "dropped": dropped}


# --------------------------------------------------------------------------
# Computations (pure, tested by scripts/test_charts.py)

def format_ratio(r):
    """How a ratio is written on the charts: 2.7x, 31x."""
    return f"{r:.0f}x" if r >= 9.95 else f"{r:.1f}x"


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
    return fixed, dict(sorted(by_series.items(), key=lambda kv: series_sort_key(kv[0])))


def series_sort_key(key):
    kernel, api = key[0], key[1] if len(key) > 1 else ""
    return (kernel, 0 if api == "vk" else 1, api)


def speedups(records):
    """Full/half speed-up per (kernel, api) in the slice the full_vs_half chart
    draws: {(kernel, api): (full_ms, half_ms, full_ms / half_ms)}."""
    fixed, by_series = pick_slice(records, "res")
    out = OrderedDict()
    for key, pts in by_series.items():
        if "full" in pts and "half" in pts:
            f, h = pts["full"]["ms"], pts["half"]["ms"]
            out[key] = (f, h, f / h)
    return out


def fragment_ratios(records):
    """Fragment/compute time per (kernel, api) in the slice compute_vs_fragment draws."""
    fixed, by_series = pick_slice(records, "stage")
    out = OrderedDict()
    for key, pts in by_series.items():
        if "compute" in pts and "fragment" in pts:
            c, f = pts["compute"]["ms"], pts["fragment"]["ms"]
            out[key] = (c, f, f / c)
    return out


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


def api_pairs(records):
    """[(gl record, vk record)] for configurations measured on both APIs."""
    by = {}
    for r in records:
        by[(r["scene"], r["kernel"], r["samples"], r["blur"], r["res"], r["size"], r["stage"], r["api"])] = r
    out = []
    for k, r in sorted(by.items(), key=lambda kv: kv[1]["id"]):
        if k[-1] == "gl" and k[:-1] + ("vk",) in by:
            out.append((r, by[k[:-1] + ("vk",)]))
    return out


def history_series(files, limit=HISTORY_MAX_LINES):
    """Configurations present in every file: (ids chosen, {id: [ms per file]}, n common).
    At most `limit`, those whose time changed most between the first and last
    file first."""
    common = [cid for cid in files[-1]["records"] if all(cid in f["records"] for f in files)]
    values = {cid: [f["records"][cid]["ms"] for f in files] for cid in common}
    order = sorted(common, key=lambda c: (-abs(math.log(values[c][-1] / values[c][0])), c))
    chosen = sorted(order[:limit], key=lambda c: -abs(values[c][-1] / values[c][0] - 1))
    return chosen, values, len(common)


# --------------------------------------------------------------------------
# Labels

def _dedupe_per_api(text):
    """"X" from "gl: X; vk: X"; the text as it is when the APIs differ."""
    if not isinstance(text, str) or not text.strip():
        return None
    parts = [p.strip() for p in text.split(";") if p.strip()]
    vals = [re.sub(r"^(gl|vk)\s*:\s*", "", p) for p in parts]
    return vals[0] if len(set(vals)) == 1 else "; ".join(parts)


def device_name(context):
    return _dedupe_per_api(context.get("cavity_device")) or context.get("host_name") or "unknown device"


def driver_name(context):
    return _dedupe_per_api(context.get("cavity_driver"))


def device_line(context, driver=True):
    """"NVIDIA H100 80GB HBM3  ·  driver 550.90.07" from the context
    ("gl: NVIDIA H100 80GB HBM3; vk: NVIDIA H100 80GB HBM3" and so on)."""
    bits = [device_name(context)]
    drv = driver_name(context)
    if drv and driver:
        bits.append("driver " + drv)
    if str(context.get("cavity_software_renderer", "")).lower() == "true":
        bits.append("SOFTWARE RENDERER (CPU times)")
    line = "  ·  ".join(bits)
    return line if len(line) <= 110 else line[:107] + "..."


def is_compute_card(context):
    dev = str(context.get("cavity_device", ""))
    return bool(re.search(r"\b(H100|H200|H800|A100|A800|A30|B100|B200|GH200|GB200|MI\d{3}\w*)\b", dev))


def fixed_line(fixed):
    """"corner · n16 · blur 4 · full res · 1920x1080 · compute" for a slice."""
    out = []
    for d in DIMS:
        if d not in fixed:
            continue
        v = fixed[d]
        if d == "samples": out.append(f"n={v}")
        elif d == "blur": out.append(f"blur {v} px")
        elif d == "res": out.append(f"{v} res")
        elif d == "size": out.append(f"{v[0]}x{v[1]}")
        elif d == "api": out.append(API_NAMES.get(v, v))
        elif d == "stage": out.append(f"{v} stage")
        elif d == "scene": out.append(f"scene {v}")
        else: out.append(str(v))
    return "  ·  ".join(out)


def series_label(key):
    kernel, api = key
    return f"{kernel} · {API_NAMES.get(api, api)}"


def file_label(f, width=32):
    name = f["name"][:-5] if f["name"].endswith(".json") else f["name"]
    if f["date"]:
        m = re.match(r"(\d{4}-\d\d-\d\d)[T ](\d\d:\d\d)", f["date"])
        date = f"{m[1]} {m[2]}" if m else f["date"][:16]
        return f"{date}\n{shorten(name, width)}"
    return shorten(name, width)


def shorten(text, n):
    return text if len(text) <= n else text[: n - 1] + "…"


def short_ids(ids):
    """Drop the id parts every id shares: returns (common text, {id: distinct text})."""
    split = {i: i.split("/") for i in ids}
    n = min(len(s) for s in split.values())
    same = [all(s[k] == split[ids[0]][k] for s in split.values()) for k in range(n)]
    common = "/".join(p for k, p in enumerate(split[ids[0]][:n]) if same[k])
    short = {i: "/".join(p for k, p in enumerate(s) if k >= n or not same[k]) or i for i, s in split.items()}
    return common, short


# --------------------------------------------------------------------------
# Drawing

class Charts:
    def __init__(self, files, outdir, title_prefix):
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
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
        kernels = sorted({r["kernel"] for f in files for r in f["records"].values()})
        palette = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2",
                   "#7f7f7f", "#bcbd22", "#17becf"]
        fixed = {"alchemy": palette[0], "hemisphere": palette[1], "ssdo": palette[2]}
        rest = [c for c in palette if c not in fixed.values()]
        self.kcolor = {}
        for k in kernels:
            self.kcolor[k] = fixed.get(k) or rest[len([1 for v in self.kcolor if v not in fixed]) % len(rest)]

    # -- helpers
    def style(self, key):
        kernel, api = key
        return dict(color=self.kcolor.get(kernel, "#333333"),
                    linestyle="-" if api == "vk" else "--",
                    marker="o" if api == "vk" else "s",
                    markersize=6, linewidth=2)

    def figure(self, width=8.5, height=5.2):
        fig, ax = self.plt.subplots(figsize=(width, height))
        return fig, ax

    def title(self, text):
        return f"{self.prefix}: {text}" if self.prefix else text

    def finish(self, name, fig, ax, title, subtitle_extra=None, legend=True, legend_kw=None, extra=None,
               device=True):
        axes = ax if isinstance(ax, (list, tuple)) else [ax]
        ax = axes[0]
        dev = device_line(self.context) if device else ""
        if dev and any(r["wall"] for r in self.records):
            dev += "  ·  some times are drained wall clock (timestamps unusable)"
        sub = "\n".join(t for t in (dev, subtitle_extra) if t)
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
        fig.tight_layout(rect=(0, 0, 1, 1 - header / height))
        png = os.path.join(self.outdir, name + ".png")
        svg = os.path.join(self.outdir, name + ".svg")
        fig.savefig(png, dpi=DPI)
        fig.savefig(svg)
        self.plt.close(fig)
        entry = {"name": name, "title": self.title(title), "png": name + ".png", "svg": name + ".svg"}
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

    def ms_axis(self, ax, values, log_if=40.0):
        lo, hi = min(values), max(values)
        if lo > 0 and hi / lo > log_if:
            ax.set_yscale("log")
            self.plain_log(ax.yaxis)
            ax.set_ylabel("GPU time (ms, log scale)")
        else:
            ax.set_ylim(0, hi * 1.12)
            ax.set_ylabel("GPU time (ms)")

    # -- 1
    def time_vs_samples(self):
        fixed, by_series = pick_slice(self.records, "samples")
        if not by_series:
            return self.skip("time_vs_samples", "no configurations that differ only in sample count")
        fig, ax = self.figure()
        xs_all, ys_all = set(), []
        for key, pts in by_series.items():
            xs = list(pts)
            ys = [pts[x]["ms"] for x in xs]
            xs_all.update(xs)
            ys_all += ys
            ax.plot(xs, ys, label=series_label(key), **self.style(key))
        ax.set_xscale("log", base=2)
        ticks = sorted(xs_all)
        ax.set_xticks(ticks)
        ax.set_xticklabels([str(t) for t in ticks])
        ax.minorticks_off()
        ax.set_xlim(min(ticks) / 1.25, max(ticks) * 1.25)
        ax.set_xlabel("samples per pixel (log2 scale)")
        self.ms_axis(ax, ys_all)
        self.finish("time_vs_samples", fig, ax, "AO GPU time vs sample count", fixed_line(fixed),
                    legend_kw=dict(loc="upper left"))

    # -- 2
    def time_vs_blur(self):
        fixed, by_series = pick_slice(self.records, "blur")
        if not by_series:
            return self.skip("time_vs_blur", "no configurations that differ only in blur radius")
        fig, ax = self.figure()
        xs_all, ys_all = set(), []
        for key, pts in by_series.items():
            xs = list(pts)
            ys = [pts[x]["ms"] for x in xs]
            xs_all.update(xs)
            ys_all += ys
            ax.plot(xs, ys, label=series_label(key), **self.style(key))
        ticks = sorted(xs_all)
        ax.set_xticks(ticks)
        ax.set_xticklabels(["0 (off)" if t == 0 else str(t) for t in ticks])
        ax.set_xlabel("blur radius (px)")
        self.ms_axis(ax, ys_all)
        self.finish("time_vs_blur", fig, ax, "AO GPU time vs bilateral blur radius", fixed_line(fixed),
                    legend_kw=dict(loc="lower right"))

    # -- 3
    def full_vs_half(self):
        fixed, _ = pick_slice(self.records, "res")
        sp = speedups(self.records)
        if not sp:
            return self.skip("full_vs_half", "no configuration measured at both full and half resolution")
        fig, ax = self.figure(width=max(6.5, 1.3 * len(sp) + 3))
        keys = list(sp)
        w = 0.38
        labels_written = {}
        fulls = [sp[k][0] for k in keys]
        halves = [sp[k][1] for k in keys]
        xs = list(range(len(keys)))
        ax.bar([x - w / 2 for x in xs], fulls, w, label="full resolution", color="#3b6ea8", zorder=3)
        ax.bar([x + w / 2 for x in xs], halves, w, label="half resolution (AO at ¼ pixels + upsample)",
               color="#9cc3e6", edgecolor="#3b6ea8", zorder=3)
        top = max(fulls + halves)
        for x, k in zip(xs, keys):
            text = format_ratio(sp[k][2])
            labels_written[series_label(k)] = text
            ax.annotate(text, (x, max(sp[k][0], sp[k][1])), xytext=(0, 4), textcoords="offset points",
                        ha="center", va="bottom", fontsize=10, fontweight="bold")
        ax.set_xticks(xs)
        ax.set_xticklabels([f"{k[0]}\n{API_NAMES.get(k[1], k[1])}" for k in keys])
        ax.set_ylim(0, top * 1.22)
        ax.set_ylabel("GPU time (ms)")
        ax.set_xlabel("kernel and API   (number above each pair: speed-up = full time / half time)")
        self.finish("full_vs_half", fig, ax, "Full vs half resolution AO", fixed_line(fixed),
                    legend_kw=dict(loc="upper left"), extra={"labels": labels_written})

    # -- 4
    def time_vs_megapixels(self):
        fixed, by_series = pick_slice(self.records, "size")
        if not by_series:
            return self.skip("time_vs_megapixels", "no configurations that differ only in image size")
        fig, (ax, ax2) = self.plt.subplots(1, 2, figsize=(11, 5.4), gridspec_kw=dict(width_ratios=(1.35, 1)))
        sizes = set()
        xmax = ymax = 0
        fits = {}
        per_mp = []
        for key, pts in by_series.items():
            st = self.style(key)
            xs = [w * h / 1e6 for (w, h) in pts]
            ys = [r["ms"] for r in pts.values()]
            sizes.update(pts)
            slope, r2 = fit_through_origin(xs, ys)
            fits[series_label(key)] = {"ms_per_mp": slope, "r2": r2}
            ax.plot(xs, ys, linestyle="none", marker=st["marker"], markersize=7, color=st["color"], zorder=3,
                    label=f"{series_label(key)}:  {slope:.3g} ms/MP,  R²={r2:.3f}")
            xe = max(xs) * 1.05
            ax.plot([0, xe], [0, slope * xe], linestyle="--", linewidth=1.2, color=st["color"], alpha=0.8, zorder=2)
            xmax, ymax = max(xmax, xe), max(ymax, max(ys), slope * xe)
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
        ax.set_ylabel("GPU time (ms)")
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
        ax2.set_ylabel("GPU time per megapixel (ms/MP)")
        ax2.set_title("cost per megapixel (dotted: fitted slope); flat = linear", loc="left", fontsize=9)
        self.finish("time_vs_megapixels", fig, [ax, ax2], "AO GPU time vs image size", fixed_line(fixed),
                    legend_kw=dict(loc="upper left", ncol=1, fontsize=8.5), extra={"fits": fits})

    # -- 5
    def gl_vs_vk(self):
        pairs = api_pairs(self.records)
        if not pairs:
            return self.skip("gl_vs_vk", "no configuration measured on both OpenGL and Vulkan")
        fig, ax = self.figure(width=7.0, height=7.0)
        vals = [v for g, k in pairs for v in (g["ms"], k["ms"])]
        lo, hi = min(vals) / 1.6, max(vals) * 1.6
        xs = [lo * (hi / lo) ** (i / 100) for i in range(101)]
        ax.fill_between(xs, [x * 0.9 for x in xs], [x * 1.1 for x in xs], color="#999999", alpha=0.22,
                        label="±10% band", zorder=1)
        ax.plot(xs, xs, color="#555555", linewidth=1, label="y = x (same time)", zorder=2)
        markers = {"compute": "o", "fragment": "^"}
        seen = set()
        for g, k in pairs:
            kern, stage = g["kernel"], g["stage"]
            ax.scatter(g["ms"], k["ms"], s=46, color=self.kcolor.get(kern, "#333333"),
                       marker=markers.get(stage, "D"), edgecolor="white", linewidth=0.6, zorder=3)
            seen.add((kern, stage))
        for kern in sorted({k for k, _ in seen}):
            ax.plot([], [], linestyle="none", marker="o", color=self.kcolor.get(kern), label=kern)
        for stage in sorted({s for _, s in seen}):
            ax.plot([], [], linestyle="none", marker=markers.get(stage, "D"), color="#777777", label=f"{stage} stage")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        self.plain_log(ax.xaxis)
        self.plain_log(ax.yaxis)
        ax.set_aspect("equal")
        ax.set_xlabel("OpenGL GPU time (ms, log scale)")
        ax.set_ylabel("Vulkan GPU time (ms, log scale)")
        within = sum(1 for g, k in pairs if abs(k["ms"] / g["ms"] - 1) <= 0.10)
        vk_faster = sum(1 for g, k in pairs if k["ms"] < g["ms"])
        text = (f"{len(pairs)} configurations on both APIs, {within} within ±10%\n"
                f"Vulkan faster in {vk_faster}, OpenGL in {len(pairs) - vk_faster} (below the line: Vulkan faster)")
        outside = sorted(((k["ms"] / g["ms"], g) for g, k in pairs if abs(k["ms"] / g["ms"] - 1) > 0.10),
                         key=lambda t: -abs(math.log(t[0])))
        if outside:
            ids = [g["id"] for g, _ in pairs]
            _, short = short_ids(ids) if len(ids) > 1 else ("", {ids[0]: ids[0]})
            text += "\noutside the band (Vulkan time vs OpenGL time):"
            for ratio, g in outside[:5]:
                text += f"\n  {shorten(short[g['id']].replace('/gl', ''), 40)}: {(ratio - 1) * 100:+.1f}%"
            if len(outside) > 5:
                text += f"\n  and {len(outside) - 5} more"
        ax.text(0.98, 0.03, text, transform=ax.transAxes, ha="right", va="bottom", fontsize=8, linespacing=1.35, multialignment="left",
                bbox=dict(boxstyle="round", facecolor="white", edgecolor="#cccccc"))
        self.finish("gl_vs_vk", fig, ax, "OpenGL vs Vulkan, same configuration",
                    "every configuration measured on both APIs (all scenes, sizes, samples)",
                    legend_kw=dict(loc="upper left"))

    # -- 6
    def compute_vs_fragment(self):
        fixed, _ = pick_slice(self.records, "stage")
        fr = fragment_ratios(self.records)
        if not fr:
            return self.skip("compute_vs_fragment", "no configuration measured in both compute and fragment stage")
        fig, ax = self.figure(width=max(6.5, 1.3 * len(fr) + 3))
        keys = list(fr)
        xs = list(range(len(keys)))
        w = 0.38
        comp = [fr[k][0] for k in keys]
        frag = [fr[k][1] for k in keys]
        frag_label = "fragment stage"
        if is_compute_card(self.context):
            frag_label = "fragment (non-representative on H100)" if "H100" in str(self.context.get("cavity_device")) \
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
            self.plain_log(ax.yaxis)
            ax.set_ylim(min(vals) / 2, max(vals) * 3)
            ax.set_ylabel("GPU time (ms, log scale)")
        else:
            ax.set_ylim(0, max(vals) * 1.22)
            ax.set_ylabel("GPU time (ms)")
        ax.set_xlabel("kernel and API   (number above each pair: fragment time / compute time)")
        self.finish("compute_vs_fragment", fig, ax, "Compute vs fragment stage", fixed_line(fixed),
                    legend_kw=dict(loc="upper left"), extra={"labels": labels_written})

    # -- 7
    def history(self):
        if len(self.files) < 2:
            return self.skip("history", "needs two or more result files")
        chosen, values, n_common = history_series(self.files)
        if not chosen:
            return self.skip("history", "no configuration is in every file")
        fig, (ax, ax2) = self.plt.subplots(1, 2, figsize=(13, 5.8), sharex=True)
        xs = list(range(len(self.files)))
        common, short = short_ids(chosen) if len(chosen) > 1 else ("", {chosen[0]: chosen[0]})
        cmap = self.plt.get_cmap("tab10")
        all_v, all_rel = [], []
        for i, cid in enumerate(chosen):
            v = values[cid]
            rel = [(x / v[0] - 1) * 100 for x in v]
            all_v += v
            all_rel += rel
            st = dict(marker="o", linewidth=1.8, color=cmap(i % 10))
            ax.plot(xs, v, label=f"{short[cid]}  {v[0]:.3g} → {v[-1]:.3g} ms  ({rel[-1]:+.1f}%)", **st)
            ax2.plot(xs, rel, **st)
        devices = {device_name(f["context"]) for f in self.files}
        drivers = {driver_name(f["context"]) for f in self.files}
        width = max(12, 110 // len(self.files))
        labels = []
        for f in self.files:
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
        self.ms_axis(ax, all_v, log_if=8.0)
        ax.set_title("median GPU time", loc="left", fontsize=9)
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
            sub = f"latest: {device_line(self.context)}  ({what_differs} differ: see x axis)\n{sub}"
        self.finish("history", fig, [ax, ax2], "GPU time across runs", sub, legend=False, device=False)

    def run(self):
        for name in CHART_NAMES:
            getattr(self, name)()


# --------------------------------------------------------------------------
# quality-cost: error against the ground truth versus AO GPU time

AO_COST_PASSES = ("ao", "depth", "pyramid", "box", "downsample", "upsample")


def load_quality(path):
    """Rows of one quality.json: [(scene, kernel, samples, res, mae)], plus the header."""
    try:
        with open(path, "rb") as f:
            data = json.loads(f.read().decode("utf-8"))
    except OSError as e:
        raise BadInput(f"charts: {path}: cannot read ({e.strerror or e})")
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise BadInput(f"charts: {path}: not JSON ({e})")
    if not isinstance(data, dict) or data.get("schema") != "cavity-quality/1" or not isinstance(data.get("rows"), list):
        raise BadInput(f"charts: {path}: not a cavity quality.json (schema cavity-quality/1 with rows)")
    res = data.get("resolution", "full")
    rows = []
    for i, r in enumerate(data["rows"]):
        if not isinstance(r, dict) or not _is_number(r.get("mae")) or not isinstance(r.get("kernel"), str) \
                or not isinstance(r.get("samples"), int):
            raise BadInput(f"charts: {path}: rows[{i}] lacks kernel, samples or a numeric mae")
        rows.append((r.get("scene", "?"), r["kernel"], r["samples"], res, float(r["mae"])))
    return data, rows


def load_pass_times(path):
    """{config id: {pass: median ms over the iteration entries}} from cavity_bench JSON."""
    try:
        with open(path, "rb") as f:
            data = json.loads(f.read().decode("utf-8"))
    except OSError as e:
        raise BadInput(f"charts: {path}: cannot read ({e.strerror or e})")
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise BadInput(f"charts: {path}: not JSON ({e})")
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        raise BadInput(f"charts: {path}: not Google Benchmark JSON (no 'benchmarks' list)")
    samples = defaultdict(lambda: defaultdict(list))
    for e in data["benchmarks"]:
        if not isinstance(e, dict) or e.get("run_type") == "aggregate" or e.get("error_occurred"):
            continue
        cfg = parse_id(e.get("name", ""), e) if isinstance(e.get("name"), str) and "@" not in e["name"] else None
        if cfg is None:
            continue
        for key, v in e.items():
            m = re.fullmatch(r"pass_(\w+)_ms", key)
            if m and _is_number(v):
                samples[config_id(cfg)][m.group(1)].append(float(v))
    if not samples:
        raise BadInput(f"charts: {path}: no benchmark entry with pass_<name>_ms counters")

    def median(v):
        v = sorted(v)
        n = len(v)
        return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])

    return data.get("context") or {}, {cid: {p: median(v) for p, v in ps.items()} for cid, ps in samples.items()}


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


def quality_cost_main(argv):
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
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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
        json.dump({"schema": "cavity-quality-cost/1", "api": args.api, "size": args.size, "device": device,
                   "quality": [{"file": q, "header": {k: v for k, v in h.items() if k != "rows"}}
                               for q, h in zip(args.quality, headers)],
                   "points": points, "unmatched": unmatched}, f, indent=2)
        f.write("\n")
    written.append(path)
    for w in written:
        print(w)
    return 0



# --------------------------------------------------------------------------
# Measured against floor (results.json)

def load_floor_rows(path):
    """One row per pass of every run of a cavity results.json: configuration id, pass, measured median
    (ms), floor (ms, or None), reason (empty with a floor), bound, and the device line of the run."""
    try:
        with open(path) as f:
            doc = json.load(f)
    except OSError as e:
        raise BadInput(f"charts floor: {path}: cannot read ({e.strerror})")
    except ValueError as e:
        raise BadInput(f"charts floor: {path}: not JSON ({e})")
    if isinstance(doc, dict) and isinstance(doc.get("benchmarks"), list):
        return bench_floor_rows(path, doc)
    if not isinstance(doc, dict) or doc.get("schema") != "cavity.results/1" or not isinstance(doc.get("runs"), list):
        raise BadInput(f"charts floor: {path}: neither a cavity results.json (schema cavity.results/1) "
                       "nor cavity_bench JSON")
    rows = []
    for run in doc["runs"]:
        try:
            device = run["device"]["name"]
            for p in run["passes"]:
                floor = p["floor"]
                rows.append({"id": run["id"], "pass": p["name"], "ms": float(p["stats"]["median_ms"]),
                             "floor": float(floor["floor_ms"]) if floor else None,
                             "bound": floor["bound"] if floor else "", "reason": p["floor_reason"], "device": device})
        except (KeyError, TypeError, ValueError) as e:
            raise BadInput(f"charts floor: {path}: run {run.get('id', '?') if isinstance(run, dict) else '?'} "
                           f"lacks a field the chart needs ({e}); written before floors existed?")
    if not rows:
        raise BadInput(f"charts floor: {path}: no runs with passes")
    return rows


def bench_floor_rows(path, doc):
    """The same rows from cavity_bench's JSON: each `<id>@<pass>` entry's median over the
    repetitions (the "median" aggregate, else the median of the iterations) and its floor_ms,
    which the runner writes where the device has a floor (bench/ROOFLINE.md)."""
    device = (doc.get("context") or {}).get("cavity_device", "")
    per = {}
    for b in doc["benchmarks"]:
        name = b.get("run_name") or b.get("name", "")
        if "@" not in name:
            continue
        cid, rest = name.split("@", 1)
        key = (cid, rest.split("/")[0])
        e = per.setdefault(key, {"iter": [], "median": None, "floor": None})
        if b.get("run_type") == "aggregate":   # its floor_ms is the aggregate's (a stddev of 0 ...)
            if b.get("aggregate_name") == "median":
                e["median"] = float(b["real_time"])
            continue
        e["iter"].append(float(b["real_time"]))
        if b.get("floor_ms") is not None:
            e["floor"] = float(b["floor_ms"])
    rows = []
    for (cid, pas), e in per.items():
        ms = e["median"] if e["median"] is not None else (statistics.median(e["iter"]) if e["iter"] else None)
        if ms is None:
            continue
        rows.append({"id": cid, "pass": pas, "ms": ms, "floor": e["floor"], "bound": "floor" if e["floor"] else "",
                     "reason": "" if e["floor"] else "no floor_ms in the benchmark JSON", "device": device})
    if not rows:
        raise BadInput(f"charts floor: {path}: no <id>@<pass> entries (cavity_bench JSON with per-pass entries)")
    return rows


def floor_main(argv):
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
        except re.error as e:
            raise BadInput(f"charts floor: --filter {args.filter!r}: not a regular expression ({e})")
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
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

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

# --------------------------------------------------------------------------

class _Parser(argparse.ArgumentParser):
    def error(self, message):
        # one line, like every other bad-usage error of the project
        print(f"charts: {message} (usage: charts.py RESULT.json [MORE.json ...] --out DIR [--title TEXT])",
              file=sys.stderr)
        sys.exit(2)


def parse_args(argv):
    p = _Parser(prog="charts", description="Charts from cavity_bench Google Benchmark JSON.")
    p.add_argument("results", nargs="+", metavar="RESULT.json")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--title", default="", metavar="TEXT", help="prefix for every chart title")
    return p.parse_args(argv)


def run_with_system_python(argv):
    """pyenv or a venv without matplotlib: Debian's python3-matplotlib lives with /usr/bin/python3,
    so every subcommand runs again there (once)."""
    if importlib.util.find_spec("matplotlib") is not None:
        return
    system = "/usr/bin/python3"
    if os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system) \
            and not os.environ.get("CAVITY_CHARTS_REEXEC"):
        os.environ["CAVITY_CHARTS_REEXEC"] = "1"
        sys.stdout.flush()
        os.execv(system, [system, os.path.abspath(__file__)] + argv)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    run_with_system_python(argv)
    if argv and argv[0] == "quality-cost":
        return quality_cost_main(argv[1:])
    if argv and argv[0] == "floor":
        return floor_main(argv[1:])
    args = parse_args(argv)
    # Validate every input before writing anything.
    try:
        files = [load_results(p) for p in args.results]
        if os.path.exists(args.out) and not os.path.isdir(args.out):
            raise BadInput(f"charts: {args.out}: --out exists and is not a folder")
    except BadInput as e:
        print(str(e), file=sys.stderr)
        return 2
    if importlib.util.find_spec("matplotlib") is None:
        print("charts: matplotlib is not installed (apt-get install python3-matplotlib)", file=sys.stderr)
        return 3
    for f in files:
        if f["dropped"]:
            print(f"charts: note: {f['path']}: left out {len(f['dropped'])} configuration(s) timed at 0 ms, "
                  f"e.g. {f['dropped'][0]}", file=sys.stderr)
    created = not os.path.isdir(args.out)
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        print(f"charts: {args.out}: cannot create the output folder ({e.strerror})", file=sys.stderr)
        return 2
    # charts a previous run wrote that this run may not: index.json must not disagree with the folder
    for name in CHART_NAMES:
        for ext in (".png", ".svg"):
            stale = os.path.join(args.out, name + ext)
            if os.path.isfile(stale):
                os.remove(stale)
    charts = Charts(files, args.out, args.title)
    try:
        charts.run()
    except BaseException:
        if created:
            import shutil
            shutil.rmtree(args.out, ignore_errors=True)
        raise
    index = {
        "charts": charts.written,
        "skipped": charts.skipped,
        "sources": [{"file": f["path"], "date": f["date"], "device": device_line(f["context"])} for f in files],
    }
    path = os.path.join(args.out, "index.json")
    with open(path, "w") as f:
        json.dump(index, f, indent=2)
        f.write("\n")
    print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
