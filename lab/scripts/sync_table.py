#!/usr/bin/env python3
"""What the narrow barriers buy: frame medians per configuration with the
narrow barriers and with CAVITY_FULL_BARRIERS=1, from the folder
lab/scripts/gpu_sync.sh leaves (narrow_1.json, full_1.json, narrow_2.json,
full_2.json, or each .json.gz). Each round's median beside the pooled one, so the spread
between two rounds of the same mode shows what a difference must beat.
Markdown on stdout.
  lab/scripts/sync_table.py FOLDER"""
import collections
import os
import statistics
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "charts"))
import cavity_json  # noqa: E402  scripts/charts/cavity_json.py: plain or gzip (X.json.gz)


def frames(path):
    out = collections.defaultdict(list)
    try:
        data = cavity_json.load(path)
    except (OSError, ValueError) as e:
        sys.exit(f"sync_table.py: {path}: {e}")
    for b in data.get("benchmarks", []):
        if b.get("run_type") == "iteration" and "@" not in b["name"]:
            out[b["name"].split("/iterations")[0]].append(b["real_time"])
    return out


def main(folder):
    runs = {}
    for mode in ("narrow", "full"):
        for r in (1, 2):
            runs[(mode, r)] = frames(os.path.join(folder, f"{mode}_{r}.json"))
    names = sorted(set().union(*[set(v) for v in runs.values()]))
    print("| configuration | narrow ms (round 1 / 2) | full ms (round 1 / 2) | full / narrow |")
    print("| --- | ---: | ---: | ---: |")
    for n in names:
        med = {k: statistics.median(v[n]) for k, v in runs.items() if v.get(n)}
        pooled = {m: statistics.median(runs[(m, 1)].get(n, []) + runs[(m, 2)].get(n, [])) for m in ("narrow", "full")}
        print(f"| {n} | {pooled['narrow']:.4f} ({med.get(('narrow', 1), 0):.4f} / {med.get(('narrow', 2), 0):.4f}) | "
              f"{pooled['full']:.4f} ({med.get(('full', 1), 0):.4f} / {med.get(('full', 2), 0):.4f}) | "
              f"{pooled['full'] / pooled['narrow']:.3f} |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
