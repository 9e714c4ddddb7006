#!/usr/bin/env python3
"""Calibrates a planted slowdown for the timing-verdict check.

    python3 scripts/plant_calibrate.py base.json planted.json --fmas 256 --target 0.05 > plant.json

base.json and planted.json are cavity_bench JSON of the same configurations,
the second run with `--plant PASS:FMAS`. The planted cost grows linearly with
the count of dependent FMAs per pixel, so for each configuration the count
that slows PASS by `target` is target x base / ((planted - base) / FMAS).
Writes {"<configuration id>": {"PASS": count}} for cavity_bench --plant-file;
says on stderr what it expects of each configuration.
"""
import argparse
import json
import re
import statistics
import sys

SUFFIX = re.compile(r"(/[a-z_]+:[^/]*|/manual_time|/real_time)+$")


def config_id(name):
    return SUFFIX.sub("", name)


def medians(path, counter):
    """Per configuration id, the median over repetitions of a counter."""
    try:
        doc = json.load(open(path))
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"plant_calibrate: {path}: {e}")
    values = {}
    for b in doc.get("benchmarks", []):
        if b.get("run_type") != "iteration" or "@" in b["name"] or b.get("error_occurred"):
            continue
        if counter in b:
            values.setdefault(config_id(b["run_name"]), []).append(b[counter])
    return {k: statistics.median(v) for k, v in values.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("base")
    ap.add_argument("planted")
    ap.add_argument("--fmas", type=int, required=True, help="the FMA count of the planted run")
    ap.add_argument("--target", type=float, required=True, help="relative slowdown wanted, e.g. 0.05")
    ap.add_argument("--pass", dest="pass_", default="ao")
    a = ap.parse_args()
    if a.fmas < 1 or not 0 < a.target < 10:
        sys.exit("plant_calibrate: --fmas must be >= 1 and --target in (0, 10)")
    counter = f"pass_{a.pass_}_ms"
    base, planted = medians(a.base, counter), medians(a.planted, counter)
    out = {}
    for cid in sorted(base):
        if cid not in planted:
            continue
        per_fma = (planted[cid] - base[cid]) / a.fmas
        if per_fma <= 0:
            print(f"plant_calibrate: {cid}: {a.fmas} FMAs cost nothing measurable; skipped", file=sys.stderr)
            continue
        count = max(1, round(a.target * base[cid] / per_fma))
        out[cid] = {a.pass_: count}
        print(f"plant_calibrate: {cid}: {a.pass_} {base[cid]:.4f} ms, {1e6 * per_fma:.3f} ns per FMA per frame, "
              f"{count} FMAs for +{100 * count * per_fma / base[cid]:.2f}%", file=sys.stderr)
    if not out:
        sys.exit("plant_calibrate: no configuration in both files")
    json.dump(out, sys.stdout, indent=1)
    print()


if __name__ == "__main__":
    main()
