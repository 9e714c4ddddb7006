#!/usr/bin/env python3
"""The timing-verdict tables from what lab/scripts/gpu_verdict.sh brought back.

    python3 lab/scripts/verdict_table.py DIR [--cavity build/harness/cavity] > table.md

DIR holds a1.json, a2.json (unchanged build) and b<N>.json (a slowdown of
N percent planted as DIR/plant<N>.json says: b1, b2, b5 in the AO pass, b10
in every pass), each may be .json.gz, *.clocks.csv (nvidia-smi every 200 ms).
Runs `cavity compare --json` (--min-change as given, default auto) for A/A
and each A/B, and prints: repetition CV per pass, the clock every
configuration ended on in every process, the A/A table, each A/B's detection
table (planted pass called slower, untouched passes called changed), the
budget check, and the clocks seen.
"""
import argparse
import csv
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

SUFFIX = re.compile(r"(/[a-z_]+:[^/]*|/manual_time|/real_time)+$")


def reps(path):
    """{(id, pass): [per-repetition medians]}, pass 'pipeline' for the benchmark time."""
    out = {}
    for b in cavity_json.load(path)["benchmarks"]:
        if b.get("run_type") != "iteration" or "@" in b["name"] or b.get("error_occurred"):
            continue
        cid = SUFFIX.sub("", b["run_name"])
        out.setdefault((cid, "pipeline"), []).append(b["real_time"])
        for k, v in b.items():
            if k.startswith("pass_") and k.endswith("_ms"):
                out.setdefault((cid, k[5:-3]), []).append(v)
    return out


def cv(v):
    return statistics.stdev(v) / statistics.mean(v) if len(v) > 1 and statistics.mean(v) else 0.0


def run_json(d, name):
    """DIR/NAME.json, or DIR/NAME.json.gz where only that exists."""
    return cavity_json.resolve(os.path.join(d, name + ".json"))


def compare(cavity, d, old, new, min_change="auto"):
    out = os.path.join(d, f"compare_{old}_{new}.json")
    with tempfile.TemporaryDirectory() as tmp:
        inputs = []
        for name in (old, new):
            path = run_json(d, name)
            if path.endswith(".gz"):   # cavity compare reads plain JSON
                inputs.append(os.path.join(tmp, name + ".json"))
                with open(inputs[-1], "wb") as f:
                    f.write(cavity_json.read_bytes(path))
            else:
                inputs.append(path)
        subprocess.run([cavity, "compare", *inputs, "--json", out, "--min-change", min_change], check=True,
                       stdout=subprocess.DEVNULL)
    return {(r["id"], r["pass"]): r for r in json.load(open(out))["rows"]}


def clocks(path):
    sm, mem, reasons = [], [], set()
    with open(path) as f:
        for row in csv.reader(f, skipinitialspace=True):
            if len(row) < 6 or not row[1].endswith("MHz"):
                continue
            sm.append(int(row[1].split()[0]))
            mem.append(int(row[2].split()[0]))
            reasons.add(row[5])
    return sm, mem, reasons


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--cavity", default=os.path.join(os.path.dirname(__file__), "..", "build", "harness", "cavity"))
    ap.add_argument("--budgets", default=os.path.join(os.path.dirname(__file__), "..", "baselines", "budgets.json"))
    ap.add_argument("--pattern", default="NVIDIA H200")
    ap.add_argument("--min-change", default="auto", help="cavity compare's --min-change (default auto)")
    a = ap.parse_args()
    d = a.dir
    planted = sorted((int(m.group(1)) for m in (re.match(r"b(\d+)\.json(\.gz)?$", f) for f in os.listdir(d)) if m),
                     key=lambda n: (n == 10, n))
    names = ["a1", "a2"] + [f"b{n}" for n in planted]
    runs = {n: reps(run_json(d, n)) for n in names if os.path.exists(run_json(d, n))}
    a1 = runs["a1"]
    a2 = runs.get("a2", {})
    ids = sorted({k[0] for k in a1})
    order = ["pipeline", "gbuffer", "downsample", "depth", "ao", "box", "blur", "upsample", "indirect", "composite"]
    present = {k[1] for k in a1}
    passes = [p for p in order if p in present] + sorted(present - set(order))

    n = max((len(v) for v in a1.values()), default=0)
    print(f"## Repetition CV (A1 and A2, {n} interleaved repetitions each)\n")
    print("| configuration | " + " | ".join(passes) + " |")
    print("|---|" + "---:|" * len(passes))
    worst = 0
    for cid in ids:
        cells = []
        for p in passes:
            c = max(cv(a1.get((cid, p), [0, 0])), cv(a2.get((cid, p), [0, 0])))
            worst = max(worst, c)
            cells.append(f"{100 * c:.2f}%" if (cid, p) in a1 else "")
        print(f"| {cid} | " + " | ".join(cells) + " |")
    print(f"\nlargest repetition CV: {100 * worst:.2f}%\n")

    print_clock_decisions(d)
    if not a2:   # lab/scripts/gpu_budget_check.sh: no A/A, no A/B tables
        return budgets_and_clocks(a, d, runs, passes)
    aa = compare(a.cavity, d, "a1", "a2", a.min_change)
    diffs = [abs(r["new_median_ms"] / r["old_median_ms"] - 1) for r in aa.values()
             if r["old_median_ms"] and r["new_median_ms"]]
    called = [k for k, r in aa.items() if r["verdict"] in ("slower", "faster")]
    print("## A/A: the unchanged build twice\n")
    print(f"- (configuration, pass) pairs: {len(aa)}; called different: {len(called)} "
          f"({100 * len(called) / max(1, len(aa)):.1f}%)")
    print(f"- largest |median change|: {100 * max(diffs):.2f}%; median |change|: {100 * statistics.median(diffs):.3f}%\n")

    for size in planted:
        name = f"b{size}"
        ab = compare(a.cavity, d, "a1", name, a.min_change)
        plant = cavity_json.load(run_json(d, f"plant{size}"))
        planted_passes = sorted({p for v in plant.values() for p in v})
        print(f"## A/B: {', '.join(planted_passes)} planted +{size}% ({name}), --min-change {a.min_change}\n")
        print("| configuration | pass | FMAs | measured change [95% interval] | p | verdict |")
        print("|---|---|---:|---|---:|---|")
        hit = total = false_alarm = untouched = 0
        for cid in ids:
            for p in passes:
                r = ab.get((cid, p))
                if not r:
                    continue
                is_planted = p in plant.get(cid, {})
                if p == "pipeline":
                    pass
                elif is_planted:
                    total += 1
                    hit += r["verdict"] == "slower"
                else:
                    untouched += 1
                    false_alarm += r["verdict"] in ("slower", "faster")
                if is_planted or (p != "pipeline" and r["verdict"] != "same"):
                    change = "-" if r["change_pct"] is None else \
                        f"{r['change_pct']:+.2f}% [{r['ci_low_pct']:+.2f}, {r['ci_high_pct']:+.2f}]"
                    print(f"| {cid} | {p} | {plant.get(cid, {}).get(p, '-')} | {change} | {'-' if r['p'] is None else format(r['p'], '.2g')} | {r['verdict']} |")
        got = [ab[(cid, p)]["change_pct"] for cid in plant for p in plant[cid]
               if (cid, p) in ab and ab[(cid, p)]["change_pct"] is not None]
        if got:
            print(f"\n- measured change of the planted passes: {min(got):+.2f}% to {max(got):+.2f}% "
                  f"(median {statistics.median(got):+.2f}%)")
        print(f"- planted passes called slower: {hit} of {total} ({100 * hit / max(1, total):.0f}%)")
        print(f"- untouched passes called changed: {false_alarm} of {untouched}\n")

    budgets_and_clocks(a, d, runs, passes)


def print_clock_decisions(d):
    """Every process's clock for every configuration: a configuration measured
    on the wall clock on a GPU has no verdict against one on timestamps."""
    print("## The clock each configuration ended on, per process\n")
    print("| run | configurations x repetitions | on GPU timestamps | on the wall clock | re-decided | cold probe overruled |")
    print("|---|---:|---:|---:|---:|---:|")
    total = wall = 0
    for f in sorted(os.listdir(d)):
        m = re.match(r"(.+)\.json(\.gz)?$", f)
        if not m:
            continue
        try:
            doc = cavity_json.load(os.path.join(d, f))
        except (OSError, ValueError):
            continue
        if not isinstance(doc, dict) or "benchmarks" not in doc:
            continue
        entries = [b for b in doc["benchmarks"]
                   if b.get("run_type") == "iteration" and "@" not in b["name"] and not b.get("error_occurred")]
        clocks = [re.search(r"clock=(\S+)", b.get("label", "")) for b in entries]
        ts = sum(1 for c in clocks if c and c.group(1) == "gpu-timestamp")
        redecided = sum(1 for b in entries if "clock-re-decided" in b.get("label", ""))
        overruled = sum(1 for b in entries if "cold-probe-overruled" in b.get("label", ""))
        total += len(entries)
        wall += len(entries) - ts
        print(f"| {m.group(1)} | {len(entries)} | {ts} | {len(entries) - ts} | {redecided} | {overruled} |")
    print(f"\n- measurements not on GPU timestamps: {wall} of {total}\n")


def budgets_and_clocks(a, d, runs, passes):
    # Budgets: each repetition of a run is one measurement, checked alone.
    try:
        budgets = next(x for x in json.load(open(a.budgets))["devices"] if x["pattern"] == a.pattern)["budgets_ms"]
    except (OSError, StopIteration, KeyError):
        budgets = None
    if budgets:
        print(f"## Budgets ({a.pattern} class in baselines/budgets.json), one check per repetition\n")
        plant10 = cavity_json.load(run_json(d, "plant10")) if os.path.exists(run_json(d, "plant10")) else {}
        print("| run | pass | repetitions over budget | of | largest median / budget |")
        print("|---|---|---:|---:|---:|")
        for name in ("a1" if "a2" not in runs else "a2", "b10"):
            if name not in runs:
                continue
            for p in passes:
                over = checked = 0
                worst = 0.0
                for (cid, q), values in runs[name].items():
                    b = budgets.get(cid, {}).get(q)
                    if q != p or b is None:
                        continue
                    for v in values:
                        checked += 1
                        over += v > b
                        worst = max(worst, v / b)
                if checked:
                    planted = name == "b10" and any(p in x for x in plant10.values())
                    print(f"| {name} | {p}{' (planted +10%)' if planted else ''} | {over} | {checked} | {worst:.3f} |")
        if "b10" in runs and plant10:
            ab = compare(a.cavity, d, "a1", "b10")
            got = [r["change_pct"] for (cid, p), r in ab.items() if p in plant10.get(cid, {}) and r["change_pct"] is not None]
            if got:
                print(f"\nplanted +10%: measured changes {min(got):+.1f}% to {max(got):+.1f}% (median {statistics.median(got):+.1f}%) "
                      f"over {len(got)} planted passes")
        print()

    print("## Clocks (nvidia-smi every 200 ms during each run)\n")
    print("| run | samples | SM MHz min / median / max | at 1980 MHz | memory MHz | event reasons |")
    print("|---|---:|---|---:|---|---|")
    for name in sorted(f[:-len(".clocks.csv")] for f in os.listdir(d) if f.endswith(".clocks.csv")):
        path = os.path.join(d, name + ".clocks.csv")
        if not os.path.exists(path):
            continue
        sm, mem, reasons = clocks(path)
        if not sm:   # no nvidia-smi where it ran (a dry run on a CPU renderer)
            print(f"| {name} | 0 | - | - | - | - |")
            continue
        at_max = sum(1 for x in sm if x >= 1980)
        print(f"| {name} | {len(sm)} | {min(sm)} / {statistics.median(sm):.0f} / {max(sm)} | "
              f"{100 * at_max / len(sm):.0f}% | {min(mem)}-{max(mem)} | {', '.join(sorted(reasons))} |")


if __name__ == "__main__":
    main()
