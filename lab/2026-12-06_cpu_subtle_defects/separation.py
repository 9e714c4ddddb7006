#!/usr/bin/env python3
"""How each candidate metric separates the subtle defects from noise.

    separation.py OUT    (OUT/defects.jsonl, noise_cpu.jsonl, noise_h100.jsonl from tier.sh,
                         or the same gzipped, as this folder holds them)

1. Each candidate's noise: its largest value between the CPU renderers' two
   APIs (noise_cpu) and between an H100 and the CPU renderers (noise_h100,
   the fast kernels left out: their H100 renders had a texel since reverted).
2. Each candidate added to the gate's metrics at the cross-device default
   tolerances, its own tolerance at MARGIN x the larger noise: per defect
   and matrix, failing configurations / changed ones, the weakest failing
   severity and how many fail under 3x.
3. The gate's own metrics with the CPU renderers' tolerances (the llvmpipe
   entry of manifest.json) and the same against the CPU noise itself.
"""
import collections
import gzip
import json
import os
import sys

DEFAULT = {"mean_abs": 0.001, "rmse": 0.003, "over": 0.002, "max_abs": 0.1}
CPU_TIER = {"mean_abs": 6e-5, "rmse": 0.002, "over": 5e-4, "max_abs": 0.1}
IMAGES = ("ao", "ao_blur", "color")


def load(path):
    if not os.path.exists(path) and os.path.exists(path + ".gz"):
        rows = [json.loads(x) for x in gzip.open(path + ".gz", "rt")]
    else:
        rows = [json.loads(x) for x in open(path)] if os.path.exists(path) else []
    return [r for r in rows if not r.get("missing")]


def size_of(cid):
    """A configuration's image size ("320x180"; a half one writes at it too)."""
    return next(p for p in cid.split("/") if "x" in p and p[0].isdigit())


def pixels(cid):
    w, h = size_of(cid).split("x")
    return int(w) * int(h)


def sized(tol, cid, at=14400):
    """CPU_TIER stated for `at` pixels, scaled to the configuration's: the
    noise is a count of pixels (manifest.json's sized_for_pixels)."""
    f = at / pixels(cid)
    return {m: t * (f ** 0.5 if m == "rmse" else 1 if m == "max_abs" else f) for m, t in tol.items()}


def table(rows, tol):
    """tol(row) -> {metric: tolerance}; rows' severity per configuration."""
    out = []
    for label in sorted({r["label"] for r in rows}):
        per = collections.defaultdict(float)
        for r in rows:
            if r["label"] == label:
                per[r["id"]] = max([per[r["id"]]] + [r[m] / t for m, t in tol(r).items() if t > 0])
        v = sorted(per.values())
        fail = [x for x in v if x > 1]
        out.append(f"{label}: {len(fail)}/{len(v)} fail, weakest {min(fail) if fail else 0:.2f}, "
                   f"{sum(1 for x in fail if x < 3)} under 3x, strongest passing {max([x for x in v if x <= 1] or [0]):.2f}")
    return out


def main():
    out = sys.argv[1]
    defects, cpu = load(f"{out}/defects.jsonl"), load(f"{out}/noise_cpu.jsonl")
    h100 = [r for r in load(f"{out}/noise_h100.jsonl") if "_fast/" not in r["id"]]
    names = [k for k in defects[0] if k not in ("label", "id", "image")]
    noise = {}
    print("## noise: largest value (CPU APIs / H100 against CPU)")
    for m in names:
        for im in IMAGES:
            a = max([r[m] for r in cpu if r["image"] == im] or [0])
            b = max([r[m] for r in h100 if r["image"] == im] or [0])
            noise[(m, im)] = max(a, b)
            print(f"{m:22s} {im:8s} {a:10.3g} {b:10.3g}")
    margin = 2.0
    print(f"\n## each candidate beside the gate's metrics, at {margin}x its noise")
    for m in names:
        if m in DEFAULT:
            continue
        print(m)
        for line in table(defects, lambda r, m=m: dict(DEFAULT, **{m: margin * noise[(m, r["image"])]})):
            print("   ", line)
    print("\n## the gate's metrics at the CPU renderers' tolerances, for any size")
    for line in table(defects + cpu, lambda r: CPU_TIER):
        print("   ", line)
    print("\n## the same, sized for 14400 pixels (kept)")
    for line in table(defects + cpu, lambda r: sized(CPU_TIER, r["id"])):
        print("   ", line)
    print("\n## the CPU noise by size: largest sum |d|, sum d^2 and pixels over 0.01 of an image")
    by = collections.defaultdict(lambda: [0.0, 0.0, 0.0])
    for r in cpu:
        n = pixels(r["id"])
        k = by[(size_of(r["id"]), r["image"])]
        k[0], k[1], k[2] = max(k[0], r["mean_abs"] * n), max(k[1], r["rmse"] ** 2 * n), max(k[2], r["over"] * n)
    for (size, im), (a, b, c) in sorted(by.items()):
        print(f"    {size:8s} {im:8s} {a:8.3f} {b:8.4f} {c:4.0f}")


if __name__ == "__main__":
    main()
