#!/usr/bin/env python3
"""Calibrates a planted slowdown for the timing-verdict check.

    python3 lab/scripts/plant_calibrate.py base.json --point 512:cal512.json --point 2048:cal2048.json \\
        --passes ao --target 0.05 > plant.json

base.json and each cal file are cavity_bench JSON of the same configurations,
the cal runs made with `--plant PASS:FMAS` (every pass in --passes at once:
passes are timed apart, so one run calibrates them all). A chain of dependent
FMAs costs little until it outlasts the memory latency it hides behind (256
cost nothing measurable in the hemisphere kernel on the H200's Vulkan), then
grows linearly; so the cost curve is taken as piecewise linear through
(0, base), (FMAS, cal) ..., extended past the last point, and inverted at
base x (1 + target). Writes {"<configuration id>": {"PASS": count}} for
cavity_bench --plant-file; says on stderr what it expects of each.
"""
import argparse
import json
import os
import re
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "charts"))
import cavity_json  # noqa: E402  scripts/charts/cavity_json.py: plain or gzip (X.json.gz)

SUFFIX = re.compile(r"(/[a-z_]+:[^/]*|/manual_time|/real_time)+$")


def config_id(name):
    return SUFFIX.sub("", name)


def medians(path):
    """{(configuration id, pass): median over repetitions of pass_<pass>_ms}."""
    try:
        doc = cavity_json.load(path)
    except (OSError, ValueError) as e:
        sys.exit(f"plant_calibrate: {path}: {e}")
    values = {}
    for b in doc.get("benchmarks", []):
        if b.get("run_type") != "iteration" or "@" in b["name"] or b.get("error_occurred"):
            continue
        for k, v in b.items():
            if k.startswith("pass_") and k.endswith("_ms"):
                values.setdefault((config_id(b["run_name"]), k[5:-3]), []).append(v)
    return {k: statistics.median(v) for k, v in values.items()}


def invert(points, wanted):
    """FMA count where the piecewise-linear curve through points reaches wanted."""
    for (k0, t0), (k1, t1) in zip(points, points[1:]):
        if t1 >= wanted and t1 > t0:
            return k0 + (wanted - t0) * (k1 - k0) / (t1 - t0)
    (k0, t0), (k1, t1) = points[-2], points[-1]
    if t1 <= t0:
        return None
    return k1 + (wanted - t1) * (k1 - k0) / (t1 - t0)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("base")
    ap.add_argument("--point", action="append", default=[], help="FMAS:FILE, a run with --plant PASS:FMAS")
    ap.add_argument("--point-file", action="append", default=[],
                    help="PLANT.json:FILE, a run with --plant-file PLANT.json (a refinement round)")
    ap.add_argument("--passes", default="ao", help="comma list of passes to plant")
    ap.add_argument("--target", type=float, required=True, help="relative slowdown wanted, e.g. 0.05")
    a = ap.parse_args()
    if not 0 < a.target < 10:
        sys.exit(f"plant_calibrate: --target {a.target}: must be in (0, 10)")
    base = medians(a.base)
    # Each point: (FMA count for a (configuration, pass), medians of that run).
    points = []
    for p in a.point:
        fmas, _, path = p.partition(":")
        if not fmas.isdigit() or not path:
            sys.exit(f"plant_calibrate: --point {p}: must be FMAS:FILE")
        points.append((lambda key, n=int(fmas): n, medians(path)))
    for p in a.point_file:
        plant_path, _, path = p.partition(":")
        try:
            plant = cavity_json.load(plant_path)
        except (OSError, ValueError) as e:
            sys.exit(f"plant_calibrate: --point-file {plant_path}: {e}")
        points.append((lambda key, plant=plant: plant.get(key[0], {}).get(key[1]), medians(path)))
    if not points:
        sys.exit("plant_calibrate: give at least one --point or --point-file")
    out = {}
    for (cid, pass_), t0 in sorted(base.items()):
        if pass_ not in a.passes.split(","):
            continue
        measured = {}
        for count_of, m in points:
            k = count_of((cid, pass_))
            if k and (cid, pass_) in m:
                measured[k] = m[(cid, pass_)]
        curve = [(0, t0)] + sorted(measured.items())
        if len(curve) < 2:
            continue
        count = invert(curve, t0 * (1 + a.target))
        if count is None:
            print(f"plant_calibrate: {cid} {pass_}: the planted FMAs cost nothing measurable; skipped", file=sys.stderr)
            continue
        out.setdefault(cid, {})[pass_] = max(1, round(count))
        shown = ", ".join(f"{k}: {t:.4f}" for k, t in curve)
        print(f"plant_calibrate: {cid} {pass_}: ms at FMAs {{{shown}}} -> {max(1, round(count))} FMAs "
              f"for +{100 * a.target:.1f}%", file=sys.stderr)
    if not out:
        sys.exit("plant_calibrate: no configuration in both files")
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
