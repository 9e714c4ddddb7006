#!/usr/bin/env python3
"""How far planted defects fail: for each render manifest of a planted
defect judged where it was rendered (cavity_render --store), the worst
ratio of a metric to its tolerance over every judged image, and how many
configurations failed.

    planted_ratios.py MANIFEST.json...      (one per defect; the name is the file's stem)

A ratio is value / tolerance for the metrics bounded above (max, mean and RMS
error, share over threshold, FLIP, share of differing pixels) and tolerance /
value for those bounded below (SSIM); PSNR is left out, its ratio being one
of RMSE's. Prints a Markdown table.
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "charts"))
import cavity_json  # noqa: E402  scripts/charts/cavity_json.py: plain or gzip (X.json.gz)

UPPER = {"max_abs": "max_abs", "mean_abs": "mean_abs", "rmse": "rmse", "over_threshold_share": "over_threshold_share",
         "flip_mean": "flip_mean_max", "differing_share": "differing_share_max"}


def worst(judged):
    m, t = judged["metrics"], judged["tolerance"]
    best, what = 0.0, ""
    for metric, tol in UPPER.items():
        if metric in m and t.get(tol, 0) > 0 and m[metric] >= 0:
            r = m[metric] / t[tol]
            if r > best:
                best, what = r, metric
    if m.get("ssim", 1) > 0 and t.get("ssim_min"):
        # 1 - SSIM against 1 - the bound: how far below it the image fell.
        r = (1 - m["ssim"]) / max(1e-12, 1 - t["ssim_min"])
        if r > best:
            best, what = r, "1-ssim"
    return best, what


def main():
    print("| defect | configurations failed | images failed / judged | worst ratio | metric | at |")
    print("| --- | ---: | ---: | ---: | --- | --- |")
    for path in sys.argv[1:]:
        m = cavity_json.load(path)
        configs, failed_configs, images, failed_images = 0, 0, 0, 0
        top = (0.0, "", "")
        for c in m["configurations"]:
            configs += 1
            bad = False
            for i in c["renders"][0]["images"]:
                k = i.get("judged")
                if not k:
                    continue
                images += 1
                failed_images += not k["passed"]
                bad |= not k["passed"]
                r, what = worst(k)
                if r > top[0]:
                    top = (r, what, c["id"] + " " + i["name"])
            failed_configs += bad
        name = os.path.basename(path).split(".")[0]
        print(f"| {name} | {failed_configs} of {configs} | {failed_images} / {images} | {top[0]:.1f}x | {top[1]} | `{top[2]}` |")


if __name__ == "__main__":
    main()
