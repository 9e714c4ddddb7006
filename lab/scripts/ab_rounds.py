#!/usr/bin/env python3
"""How many rounds of `cavity ab` it took to call a planted change.

    python3 lab/scripts/ab_rounds.py AB_DIR [--pass ao] [--cavity build/harness/cavity] > rounds.md

AB_DIR is one `cavity ab --out` folder (lab/scripts/gpu_ab.sh brings back ab1/,
A against A with a plant, and aa/, A against A): a_<r>.json and b_<r>.json,
one process per side and round. For every prefix of 3..R rounds it merges
each side's first rounds (repetition k = round k, as `cavity ab` does),
compares them with `cavity compare --min-change auto`, and prints how many
configurations had the planted pass called slower, how many untouched
(configuration, pass) pairs were called different, and the seconds the
prefix took (from the processes' start times in their JSON). The pipeline row,
which holds the planted pass, counts as neither. Exit 0; 2 on a
folder without rounds.
"""
import argparse
import datetime
import glob
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "charts"))
import cavity_json  # noqa: E402  scripts/charts/cavity_json.py: plain or gzip (X.json.gz)


def rounds(d):
    found = {}
    for f in glob.glob(os.path.join(d, "[ab]_*.json*")):
        m = re.match(r"([ab])_(\d+)\.json(\.gz)?$", os.path.basename(f))
        if m:
            found.setdefault(int(m.group(2)), {})[m.group(1)] = f
    return [found[r] for r in sorted(found) if len(found[r]) == 2]


def merge(files, path):
    json.dump(cavity_json.merge_rounds(files), open(path, "w"))


def started(f):
    """When the process began: Google Benchmark's context date (to the second)."""
    return datetime.datetime.fromisoformat(cavity_json.load(f)["context"]["date"]).timestamp()


def elapsed(rs, n):
    """Seconds from the first process's start to the end of round n, a
    process's run taken as the mean gap between starts."""
    starts = sorted(started(f) for r in rs for f in r.values())
    per = (starts[-1] - starts[0]) / max(1, len(starts) - 1)
    return max(started(f) for f in rs[n - 1].values()) - starts[0] + per


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--pass", dest="planted", default="ao", help="the planted pass (default ao)")
    ap.add_argument("--cavity", default=os.path.join(os.path.dirname(__file__), "..", "build", "harness", "cavity"))
    a = ap.parse_args()
    rs = rounds(a.dir)
    if len(rs) < 3:
        print(f"ab_rounds: {a.dir}: {len(rs)} complete rounds (a_<r>.json and b_<r>.json); need 3", file=sys.stderr)
        return 2
    print(f"## {os.path.basename(os.path.normpath(a.dir))}: rounds needed, --min-change auto\n")
    print(f"| rounds | seconds | configurations | {a.planted} slower | {a.planted} inconclusive | "
          "untouched pairs | untouched called different |")
    print("|---:|---:|---:|---:|---:|---:|---:|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in range(3, len(rs) + 1):
            for side in "ab":
                merge([r[side] for r in rs[:n]], os.path.join(tmp, side + ".json"))
            out = os.path.join(tmp, "compare.json")
            subprocess.run([a.cavity, "compare", os.path.join(tmp, "a.json"), os.path.join(tmp, "b.json"),
                            "--min-change", "auto", "--json", out], check=True, stdout=subprocess.DEVNULL)
            rows = json.load(open(out))["rows"]
            planted = [r for r in rows if r["pass"] == a.planted]
            # The pipeline's time holds the planted pass: neither planted nor untouched.
            rest = [r for r in rows if r["pass"] not in (a.planted, "pipeline")]
            slower = sum(r["verdict"] == "slower" for r in planted)
            unsure = sum(r["verdict"] == "inconclusive" for r in planted)
            moved = sum(r["verdict"] in ("slower", "faster") for r in rest)
            print(f"| {n} | {elapsed(rs, n):.0f} | {len(planted)} | {slower} | {unsure} | {len(rest)} | {moved} |")
    # What the plant delivered with every round in: a miss where it came in
    # under its target is the calibration's, not the verdict's.
    changes = [r["change_pct"] for r in planted if r["change_pct"] is not None]
    if changes:
        print(f"\n- measured change of the planted passes, {len(rs)} rounds: "
              f"{min(changes):+.2f}% to {max(changes):+.2f}% (median {statistics.median(changes):+.2f}%)")
    # The misses, where the run called any (an A/A run calls none, and has no plant to miss).
    for r in planted if any(r["verdict"] == "slower" for r in planted) else []:
        if r["verdict"] != "slower":
            what = r["reason"] or r["verdict"]
            if r["change_pct"] is None:
                print(f"- not called: {r['id']}: {what}")
            else:
                print(f"- not called: {r['id']}: {r['change_pct']:+.2f}% [{r['ci_low_pct']:+.2f}, "
                      f"{r['ci_high_pct']:+.2f}], p = {r['p']:.2g}, {what}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
