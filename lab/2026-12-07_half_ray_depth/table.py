#!/usr/bin/env python3
"""The before/after MAE table from quality.sh's files (markdown on stdout).
    table.py   (reads quality_{before,after}_WxH.json beside it)"""
import json
import os

here = os.path.dirname(os.path.abspath(__file__))
print("| size | scene | kernel | n | MAE before | MAE after | mean AO before / after | truth |")
print("| --- | --- | --- | ---: | ---: | ---: | ---: | ---: |")
for res in ("160x90", "320x180", "640x360"):
    rows = {}
    for side in ("before", "after"):
        path = os.path.join(here, f"quality_{side}_{res}.json")
        if not os.path.exists(path):
            continue
        for r in json.load(open(path))["rows"]:
            rows.setdefault((r["scene"], r["kernel"], r["samples"]), {})[side] = r
    for (scene, kernel, n), s in sorted(rows.items()):
        b, a = s.get("before"), s.get("after")
        if not (a and b):
            continue
        print(f"| {res} | {scene} | `{kernel}` | {n} | {b['mae']:.4f} | {a['mae']:.4f} | "
              f"{b['mean_ao']:.3f} / {a['mean_ao']:.3f} | {a['mean_truth']:.3f} |")
