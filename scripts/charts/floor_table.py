#!/usr/bin/env python3
"""Medians per configuration and pass, with each pass's floor,
measured/floor and register count (where the driver reports one), from
cavity_bench JSON files with repetitions (what a floor run
leaves), and each configuration's pipeline (every pass but the G-buffer:
the median of the repetitions' sums against the sum of the floors, when
every one of those passes has a floor). Markdown on stdout.
  scripts/charts/floor_table.py BENCH.json[.gz] [BENCH.json[.gz] ...]"""
import collections
import statistics
import sys

import cavity_json   # scripts/charts/cavity_json.py: plain or gzip (X.json.gz)


def main(paths):
    rows = collections.defaultdict(lambda: collections.defaultdict(list))
    for path in paths:
        try:
            data = cavity_json.load(path)
        except (OSError, ValueError) as e:
            sys.exit(f"floor_table.py: {path}: {e}")
        for b in data.get("benchmarks", []):
            if b.get("run_type") != "iteration" or "@" in b["name"]:
                continue
            name = b["name"].split("/iterations")[0]
            pipeline = 0.0
            for k, v in b.items():
                if k.startswith("pass_") and k.endswith("_ms"):
                    rows[name]["ms:" + k[5:-3]].append(v)
                    pipeline += v if k != "pass_gbuffer_ms" else 0.0
                elif k.startswith("floor_") and k.endswith("_ms"):
                    rows[name]["floor:" + k[6:-3]].append(v)
                elif k.startswith("registers_"):
                    rows[name]["registers:" + k[10:]].append(v)
            rows[name]["pipeline"].append(pipeline)
            rows[name]["frame"].append(b["real_time"])
            rows[name]["sm_mhz"].append(b.get("sm_mhz_median", 0))
    print("| configuration | pass | median ms | floor ms | measured / floor | registers |")
    print("| --- | --- | ---: | ---: | ---: | ---: |")
    for name, r in sorted(rows.items()):
        for key in r:
            if not key.startswith("ms:"):
                continue
            p = key[3:]
            ms = statistics.median(r[key])
            fl = r.get("floor:" + p)
            f = statistics.median(fl) if fl else None
            regs = r.get("registers:" + p)
            print(f"| {name} | {p} | {ms:.4f} | {f'{f:.4f}' if f else '-'} | {f'{ms / f:.2f}x' if f else '-'} | "
                  f"{f'{max(regs):.0f}' if regs else '-'} |")
        passes = [key[3:] for key in r if key.startswith("ms:") and key != "ms:gbuffer"]
        floors = [statistics.median(r["floor:" + p]) for p in passes if r.get("floor:" + p)]
        ms = statistics.median(r["pipeline"])
        f = sum(floors) if passes and len(floors) == len(passes) else None
        print(f"| {name} | pipeline ({len(passes)} passes, the G-buffer not counted) | {ms:.4f} | "
              f"{f'{f:.4f}' if f else '-'} | {f'{ms / f:.2f}x' if f else '-'} | |")
        print(f"| {name} | frame (n={len(r['frame'])}, SM {statistics.median(r['sm_mhz']):.0f} MHz) | "
              f"{statistics.median(r['frame']):.4f} | | | |")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
