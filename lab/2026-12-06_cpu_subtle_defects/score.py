#!/usr/bin/env python3
"""Per defect and matrix: the configurations it changed, how many failed,
and the weakest and median severity over the changed ones (the largest
ratio of a metric to its tolerance, as the gate page orders failures).

    score.py OUT
"""
import glob
import json
import os
import statistics
import sys


def over(v, limit):
    return v / limit if limit > 0 else (1e300 if v > 0 else 0)


def severity(r, tile=True):
    worst = 0
    for i in r["images"]:
        m, t = i.get("metrics"), i["tolerance"]
        if not m:
            continue
        worst = max(worst, over(m["max_abs"], t["max_abs"]), over(m["mean_abs"], t["mean_abs"]),
                    over(m["rmse"], t["rmse"]), over(m["over_threshold_share"], t["over_threshold_share"]),
                    over(1 - m["ssim"], 1 - t["ssim_min"]),
                    t["psnr_min"] / m["psnr"] if 0 < m["psnr"] < 1e299 else 0)
        if m["flip_mean"] >= 0:
            worst = max(worst, over(m["flip_mean"], t["flip_mean_max"]),
                        over(m["differing_share"], t["differing_share_max"]))
        if tile and "tile_bias" in m:
            worst = max(worst, over(m["tile_bias"], t["tile_bias_max"]))
    return worst


def main():
    rows = []
    for path in sorted(glob.glob(os.path.join(sys.argv[1], "*", "gate.json"))):
        name = os.path.basename(os.path.dirname(path))
        g = json.load(open(path))
        changed = [r for r in g["results"] if any(i.get("metrics") and i["metrics"]["max_abs"] > 0 for i in r["images"])]
        failed = [r for r in changed if r["verdict"] == "fail"]
        old = sorted(severity(r, tile=False) for r in changed)
        new = sorted(severity(r) for r in changed)
        bias = sorted(max((i["metrics"].get("tile_bias", 0) for i in r["images"] if i.get("metrics")), default=0)
                      for r in changed)
        fmt = lambda v: f"{v:.2f}" if v < 1e299 else "inf"
        rows.append((name, len(g["results"]), len(changed), len(failed),
                     sum(1 for v in old if v > 1), fmt(old[0]) if old else "-", fmt(new[0]) if new else "-",
                     fmt(statistics.median(new)) if new else "-", f"{bias[0]:.4f}" if bias else "-"))
    print("| defect-matrix | configs | changed | failed | failed without tile bias | weakest without | weakest with | median with | smallest tile bias |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for r in rows:
        print("| " + " | ".join(str(x) for x in r) + " |")


if __name__ == "__main__":
    main()


def failing_table(out, tile=True):
    """Per defect: the weakest failing configuration's severity, and the
    strongest changed one that passed: the gap the tolerances sit in."""
    print("| defect-matrix | failed | weakest failing | passing changed | strongest passing |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for path in sorted(glob.glob(os.path.join(out, "*", "gate.json"))):
        g = json.load(open(path))
        changed = [r for r in g["results"] if any(i.get("metrics") and i["metrics"]["max_abs"] > 0 for i in r["images"])]
        sev = [(severity(r, tile), r) for r in changed]
        fail = sorted(s for s, r in sev if s > 1)
        ok = sorted(s for s, r in sev if s <= 1)
        print(f"| {os.path.basename(os.path.dirname(path))} | {len(fail)} | {fail[0]:.2f} | {len(ok)} | "
              + (f"{ok[-1]:.2f}" if ok else "-") + " |" if fail else " | 0 | - | - | - |")
