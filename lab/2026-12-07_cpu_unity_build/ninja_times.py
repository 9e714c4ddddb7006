#!/usr/bin/env python3
"""Compile and link seconds per top folder from ninja logs (.ninja_log, or
.gz), one column per log, and each log's span (first start to last end).
A step with several outputs is counted once.
    ninja_times.py LOG [LOG...]
"""
import collections
import gzip
import sys


def read(path):
    opener = gzip.open if path.endswith(".gz") else open
    per, steps, seen, span = collections.Counter(), collections.Counter(), set(), 0
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("#"):
                continue
            start, end, _, out, cmdhash = line.rstrip("\n").split("\t")
            span = max(span, int(end))
            if (start, end, cmdhash) in seen:
                continue
            seen.add((start, end, cmdhash))
            where = out.split("/")[0] if out.endswith(".o") else "(links and generated files)"
            per[where] += int(end) - int(start)
            steps[where] += 1
    return per, steps, span


def main():
    logs = [read(p) for p in sys.argv[1:]]
    names = sorted({k for per, _, _ in logs for k in per}, key=lambda k: -logs[0][0][k])
    print("| folder | " + " | ".join(f"log {i + 1}: s (steps)" for i in range(len(logs))) + " |")
    print("| --- |" + " ---: |" * len(logs))
    for k in names:
        print(f"| {k} | " + " | ".join(f"{per[k] / 1000:.0f} ({steps[k]})" for per, steps, _ in logs) + " |")
    print("| all steps | " + " | ".join(f"{sum(per.values()) / 1000:.0f}" for per, _, _ in logs) + " |")
    print("| span (wall) | " + " | ".join(f"{span / 1000:.0f}" for _, _, span in logs) + " |")


if __name__ == "__main__":
    main()
