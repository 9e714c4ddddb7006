"""How things are written on the charts: ratios, devices and drivers from a
file's context, a slice's fixed values, series and file names."""

import re

from .inputs import DIMS

API_NAMES = {"gl": "OpenGL", "vk": "Vulkan"}


def format_ratio(r):
    """How a ratio is written on the charts: 2.7x, 31x."""
    return f"{r:.0f}x" if r >= 9.95 else f"{r:.1f}x"


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
        bits.append("CPU renderer")
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
        elif d == "params":
            if v: out.append(v.replace("/", " "))
        else: out.append(str(v))
    if "left_out" in fixed:
        left, total = fixed["left_out"]
        out.append(f"the first {total - left} of {total} series (--filter picks others)")
    return "  ·  ".join(out)


def series_label(key):
    kernel, api = key
    return f"{kernel} · {API_NAMES.get(api, api)}"


def file_label(f, width=32):
    name = re.sub(r"\.json(\.gz)?$", "", f["name"])
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


def clock_name(clock, software):
    """How one record's clock is written on a chart. A CPU renderer's
    "timestamps" are the renderer's own account of its work on the CPU, not a
    GPU's, so they never read "GPU"."""
    if clock == "gpu-timestamp":
        return "timestamps, CPU renderer" if software else "GPU timestamps"
    if clock == "wall":
        return "wall clock, CPU renderer" if software else "wall clock (GPU timestamps unusable)"
    if clock == "mixed":
        return "clocks mixed within a configuration's repetitions"
    return "clock not recorded"


def clock_text(records):
    """(axis text, subtitle line or "") for the records a chart draws: the
    one clock they were timed on, or, where they differ, that they do and
    how many on each."""
    counts = {}
    for r in records:
        name = clock_name(r.get("clock"), r.get("software"))
        counts[name] = counts.get(name, 0) + 1
    if len(counts) == 1:
        name = next(iter(counts))
        return name, f"clock: {name}"
    parts = ", ".join(f"{n} on {name}" for name, n in sorted(counts.items(), key=lambda kv: -kv[1]))
    return "mixed clocks, see subtitle", f"MIXED CLOCKS in this chart: {parts}; times on different clocks do not compare"


def time_label(records, what="AO pipeline time", log=False):
    """The time axis: what was timed, its unit, scale and clock."""
    clock, _ = clock_text(records)
    return f"{what} (ms{', log scale' if log else ''})\n{clock}"
