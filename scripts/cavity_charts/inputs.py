"""Reading the inputs of every chart: Google Benchmark JSON from cavity_bench
(load_results for the time charts, load_pass_times for quality-cost,
bench_floor_rows for floor), `cavity quality`'s quality.json (load_quality)
and `cavity run`'s results.json (load_floor_rows). Each file may be gzip
(X.json.gz, as bench/results/ keeps them): see scripts/cavity_json.py.

Every loader raises BadInput with the one line printed (naming the file)
when a file is not usable.
"""

import json
import math
import os
import re
import statistics
from collections import OrderedDict, defaultdict

import cavity_json

DIMS = ("scene", "kernel", "samples", "blur", "res", "size", "api", "stage")
TIME_UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


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


def is_number(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def read_json(path, prefix):
    """The parsed JSON of path (plain or gzip); BadInput "<prefix>: <path>: ..." otherwise."""
    try:
        raw = cavity_json.read_bytes(path)
    except OSError as e:
        raise BadInput(f"{prefix}: {path}: cannot read ({e.strerror or e})")
    except cavity_json.BadGzip as e:
        raise BadInput(f"{prefix}: {path}: {e}")
    try:
        return json.loads(raw.decode("utf-8"))
    except UnicodeDecodeError:
        raise BadInput(f"{prefix}: {path}: not JSON (not UTF-8 text)")
    except json.JSONDecodeError as e:
        raise BadInput(f"{prefix}: {path}: not JSON ({e.msg} at line {e.lineno} column {e.colno})")


def load_results(path):
    """Reads and checks one Google Benchmark JSON file. Returns
    {"path", "name", "date", "context", "records": {id: record}, "dropped"};
    a record is the configuration (DIMS) plus "id", "ms" and "wall". Raises BadInput
    with the one-line message (naming the file) when it is not usable."""
    def bad(what):
        return BadInput(f"charts: {path}: {what}")

    data = read_json(path, "charts")
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
        if not is_number(e.get("real_time")):
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



def load_quality(path):
    """Rows of one quality.json: [(scene, kernel, samples, res, mae)], plus the header."""
    try:
        data = cavity_json.load(path)
    except OSError as e:
        raise BadInput(f"charts: {path}: cannot read ({e.strerror or e})")
    except ValueError as e:   # not UTF-8, not JSON, a broken gzip
        raise BadInput(f"charts: {path}: not JSON ({e})")
    # cavity-quality/1 is the same document under its first name (the results
    # committed before every schema was named cavity.X/N).
    schemas = ("cavity.quality/1", "cavity-quality/1")
    if not isinstance(data, dict) or data.get("schema") not in schemas or not isinstance(data.get("rows"), list):
        raise BadInput(f"charts: {path}: not a cavity quality.json (schema cavity.quality/1 with rows)")
    res = data.get("resolution", "full")
    rows = []
    for i, r in enumerate(data["rows"]):
        if not isinstance(r, dict) or not is_number(r.get("mae")) or not isinstance(r.get("kernel"), str) \
                or not isinstance(r.get("samples"), int):
            raise BadInput(f"charts: {path}: rows[{i}] lacks kernel, samples or a numeric mae")
        rows.append((r.get("scene", "?"), r["kernel"], r["samples"], res, float(r["mae"])))
    return data, rows


def load_pass_times(path):
    """{config id: {pass: median ms over the iteration entries}} from cavity_bench JSON."""
    try:
        data = cavity_json.load(path)
    except OSError as e:
        raise BadInput(f"charts: {path}: cannot read ({e.strerror or e})")
    except ValueError as e:   # not UTF-8, not JSON, a broken gzip
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
            if m and is_number(v):
                samples[config_id(cfg)][m.group(1)].append(float(v))
    if not samples:
        raise BadInput(f"charts: {path}: no benchmark entry with pass_<name>_ms counters")

    def median(v):
        v = sorted(v)
        n = len(v)
        return v[n // 2] if n % 2 else 0.5 * (v[n // 2 - 1] + v[n // 2])

    return data.get("context") or {}, {cid: {p: median(v) for p, v in ps.items()} for cid, ps in samples.items()}



def load_floor_rows(path):
    """One row per pass of every run of a cavity results.json: configuration id, pass, measured median
    (ms), floor (ms, or None), reason (empty with a floor), bound, and the device line of the run."""
    try:
        doc = cavity_json.load(path)
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

