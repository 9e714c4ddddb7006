#!/usr/bin/env python3
"""Per pipeline and API, the worst value of every image metric in gate runs.

    python3 scripts/charts/gate_metrics.py out/gate/gate.json [more gate.json ...] > metrics.md

What a device class's tolerances in baselines/manifest.json should be set
from: for each pipeline (kernel, full|half) and API, over every configuration,
repetition and image, the largest max/mean absolute error, RMSE and share over
the pixel threshold, the smallest PSNR and SSIM, the largest FLIP (composite).
"""
import math
import sys
from collections import defaultdict

import cavity_json   # scripts/charts/cavity_json.py: plain or gzip (X.json.gz)

WORST = {"max_abs": max, "mean_abs": max, "rmse": max, "over_threshold_share": max, "psnr": min, "ssim": min,
         "flip_mean": max}


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__.strip().splitlines()[2])
    rows = defaultdict(dict)
    counts = defaultdict(int)
    for path in sys.argv[1:]:
        doc = cavity_json.load(path)
        for r in doc["results"]:
            if r.get("error"):
                continue
            parts = r["id"].split("/")
            key = (parts[1], parts[4], parts[6], parts[7], parts[5])   # kernel, full|half, api, stage, size
            for img in r["images"]:
                m = img.get("metrics")
                if not m:
                    continue
                counts[key] += 1
                for name, pick in WORST.items():
                    v = m.get(name)
                    if v is None or (name == "flip_mean" and v < 0) or (isinstance(v, float) and math.isinf(v)):
                        continue
                    cell = rows[key].get(name)
                    rows[key][name] = v if cell is None else pick(cell, v)
    print("| pipeline | res | API | stage | size | images | max abs | mean abs | RMSE | over thr. | PSNR min | SSIM min | FLIP max |")
    print("|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    fmt = lambda v, f: "-" if v is None else f.format(v)
    for key in sorted(rows):
        m = rows[key]
        print(f"| {' | '.join(key)} | {counts[key]} | {fmt(m.get('max_abs'), '{:.2g}')} | {fmt(m.get('mean_abs'), '{:.2g}')} | "
              f"{fmt(m.get('rmse'), '{:.2g}')} | {fmt(m.get('over_threshold_share'), '{:.2%}')} | "
              f"{fmt(m.get('psnr'), '{:.1f}')} | {fmt(m.get('ssim'), '{:.5f}')} | {fmt(m.get('flip_mean'), '{:.4f}')} |")


if __name__ == "__main__":
    main()
