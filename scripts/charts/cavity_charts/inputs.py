"""Reading the inputs of every chart: Google Benchmark JSON from cavity_bench
and `cavity run`'s results.json: load_results for the time charts and
quality-cost's cost, load_floor_rows (bench_floor_rows) for floor, and
`cavity quality`'s quality.json (load_quality). Each file may be gzip
(X.json.gz, as recorded runs are kept): see scripts/charts/cavity_json.py.

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

from . import spread

# params: a kernel's own parameters as the id names them ("directions=8/
# falloff=0.5"; "" at their defaults), so that configurations differing only
# there stay apart.
DIMS = ("scene", "kernel", "samples", "blur", "params", "res", "size", "api", "stage")
TIME_UNIT_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


class BadInput(Exception):
    """Input that is not usable; the message is the one line printed."""


# --------------------------------------------------------------------------
# Parsing

ID_RE = re.compile(r"^(?P<scene>[^/]+)/(?P<kernel>[^/]+)/n(?P<samples>\d+)/b(?P<blur>\d+)/"
                   r"(?P<params>(?:[^/=]+=[^/]+/)*)(?P<res>full|half)/(?P<w>\d+)x(?P<h>\d+)/(?P<api>gl|vk)/(?P<stage>compute|fragment)$")
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
                "blur": int(m["blur"]), "params": m["params"].rstrip("/"), "res": m["res"], "size": (int(m["w"]), int(m["h"])),
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
        elif "=" in p: cfg["params"] = (cfg["params"] + "/" if "params" in cfg else "") + p
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
    cfg.setdefault("params", "")
    if len(rest) >= 2:
        cfg.setdefault("scene", rest[0])
        cfg.setdefault("kernel", rest[1])
    if all(k in cfg for k in DIMS):
        return cfg
    return None


def config_id(cfg):
    w, h = cfg["size"]
    params = cfg["params"] + "/" if cfg.get("params") else ""
    return (f"{cfg['scene']}/{cfg['kernel']}/n{cfg['samples']}/b{cfg['blur']}/{params}{cfg['res']}/"
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
    """Reads and checks one file the time charts draw: cavity_bench's Google
    Benchmark JSON or `cavity run`'s results.json (cavity.results/1). Returns
    {"path", "name", "date", "context", "records": {id: record}, "dropped", "format"};
    a record is the configuration (DIMS) plus "id", "ms" (the median), "q25",
    "q75", "n" and "per" (its samples' spread: spread.summary), "times" (the samples),
    "clock" (gpu-timestamp, wall or mixed), "software" (a CPU renderer) and
    "passes" ({pass: [ms per sample]}). Raises BadInput with the one-line
    message (naming the file) when it is not usable."""
    data = read_json(path, "charts")
    if isinstance(data, dict) and data.get("schema") == RESULTS_SCHEMA:
        return results_json_records(path, data)
    if not isinstance(data, dict) or not isinstance(data.get("benchmarks"), list):
        raise BadInput(f"charts: {path}: neither Google Benchmark JSON (no 'benchmarks' list) nor a cavity "
                       f"results.json (schema {RESULTS_SCHEMA})")
    return benchmark_records(path, data)


RESULTS_SCHEMA = "cavity.results/1"
PASS_COUNTER = re.compile(r"pass_(\w+)_ms")
# The G-buffer stands for the engine's own: cavity_bench's time leaves it out
# and so does the AO pipeline taken from a results.json.
ENGINE_PASSES = ("gbuffer",)


def clock_of(label):
    """gpu-timestamp or wall from a cavity_bench label ("clock=wall mode=drained ..."), else None."""
    m = re.search(r"\bclock=([\w-]+)", label) if isinstance(label, str) else None
    return m.group(1) if m else None


def pooled_clock(clocks):
    found = {c for c in clocks if c}
    return found.pop() if len(found) == 1 else "mixed" if found else None


def benchmark_records(path, data):
    def bad(what):
        return BadInput(f"charts: {path}: {what}")

    context = data.get("context")
    if context is not None and not isinstance(context, dict):
        raise bad("not Google Benchmark JSON ('context' is not an object)")
    context = context or {}
    software = str(context.get("cavity_software_renderer", "")).lower() == "true"
    groups = defaultdict(lambda: {"median": [], "mean": [], "iteration": [], "cfg": None, "clocks": [],
                                  "passes": defaultdict(list)})
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
        if e["real_time"] < 0:  # as cavity compare and history ingest: never measured, the file is wrong
            raise bad(f"benchmarks[{i}] '{e['name']}': real_time {e['real_time']}: a time must be >= 0")
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
        if kind == "iteration":
            g["clocks"].append(clock_of(e.get("label")))
            for key, v in e.items():
                m = PASS_COUNTER.fullmatch(key)
                if m and is_number(v):
                    g["passes"][m.group(1)].append(float(v))
    if not groups:
        n = len(data["benchmarks"])
        raise bad(f"no usable benchmark entries (none of its {n} is named by a Cavity configuration id "
                  "and has a time)" if n else "no benchmark entries ('benchmarks' is empty)")
    records = OrderedDict()
    dropped = []
    for cid, g in groups.items():
        # each iteration entry is one repetition; the file's own median, where it has one, is the centre
        samples = g["iteration"]
        centre = g["median"][0] if g["median"] else None
        if not samples:
            samples = g["mean"]
        st = spread.summary(samples, centre)
        if st["ms"] > 0:
            records[cid] = dict(g["cfg"], id=cid, times=samples, per="repetitions",
                                clock=pooled_clock(g["clocks"]),
                                software=software, passes=dict(g["passes"]), **st)
        else:
            dropped.append(cid)  # a zero time is a timer that did not run; it has no ratio or log
    if not records:
        raise bad("no usable benchmark entries (every time is zero)")
    date = context.get("date") if isinstance(context.get("date"), str) else None
    return {"path": path, "name": os.path.basename(path), "date": date, "context": context, "records": records,
            "dropped": dropped, "format": "google-benchmark"}


def results_json_records(path, doc):
    """The records of a results.json: one per run, its samples the frames. A
    frame's AO pipeline time is the sum of its passes but the G-buffer (what
    cavity_bench times, and what `cavity quality --cost` reads from a
    results.json), so the two formats chart the same quantity."""
    def bad(what):
        return BadInput(f"charts: {path}: {what}")

    runs = doc.get("runs")
    if not isinstance(runs, list):
        raise bad(f"not a cavity results.json ('runs' is not a list; schema {RESULTS_SCHEMA})")
    records, dropped = OrderedDict(), []
    devices, drivers, software_any = {}, {}, False
    for i, run in enumerate(runs):
        if not isinstance(run, dict):
            raise bad(f"runs[{i}] is not an object")
        rid = run.get("id")
        cfg = parse_id(rid) if isinstance(rid, str) else None
        if cfg is None:
            raise bad(f"runs[{i}] id {rid!r} is not a configuration id "
                      "(scene/kernel/nS/bB/full|half/WxH/gl|vk/compute|fragment)")
        clock = run.get("clock")
        if clock not in ("gpu-timestamp", "wall"):
            raise bad(f"runs[{i}] '{rid}': clock {clock!r} (gpu-timestamp or wall)")
        passes = run.get("passes")
        if not isinstance(passes, list) or not passes:
            raise bad(f"runs[{i}] '{rid}': no 'passes' list")
        by_pass = OrderedDict()
        for j, p in enumerate(passes):
            samples = p.get("samples_ms") if isinstance(p, dict) else None
            if not isinstance(p, dict) or not isinstance(p.get("name"), str) or not isinstance(samples, list) \
                    or not samples or not all(is_number(v) for v in samples):
                raise bad(f"runs[{i}] '{rid}': passes[{j}] has no name or no numeric 'samples_ms'")
            by_pass[p["name"]] = [float(v) for v in samples]
        pipeline = [n for n in by_pass if n not in ENGINE_PASSES]
        lengths = {len(by_pass[n]) for n in pipeline}
        if not pipeline or len(lengths) != 1:
            raise bad(f"runs[{i}] '{rid}': its passes' samples_ms differ in length ({sorted(lengths)} frames); "
                      "one sample per frame is needed to add them up")
        samples = [sum(by_pass[n][k] for n in pipeline) for k in range(lengths.pop())]
        dev = run.get("device") if isinstance(run.get("device"), dict) else {}
        software = bool(dev.get("software_renderer"))
        software_any |= software
        devices.setdefault(cfg["api"], dev.get("name") or "unknown device")
        if dev.get("driver"):
            drivers.setdefault(cfg["api"], dev["driver"])
        st = spread.summary(samples)
        if st["ms"] > 0:
            records[rid] = dict(cfg, id=rid, times=samples, per="frames", clock=clock, software=software,
                                passes=dict(by_pass), **st)
        else:
            dropped.append(rid)
    if not records:
        raise bad("no runs with a time" if runs else "no runs ('runs' is empty)")
    context = {"cavity_device": "; ".join(f"{a}: {d}" for a, d in sorted(devices.items())),
               "cavity_driver": "; ".join(f"{a}: {d}" for a, d in sorted(drivers.items())),
               "cavity_software_renderer": "true" if software_any else "false"}
    date = doc.get("created_utc") if isinstance(doc.get("created_utc"), str) else None
    if date:
        context["date"] = date
    return {"path": path, "name": os.path.basename(path), "date": date, "context": context, "records": records,
            "dropped": dropped, "format": "results.json"}


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

