#!/usr/bin/env python3
"""Writes timing budgets into baselines/budgets.json from a gate run or a benchmark run.

    python3 scripts/update_budgets.py out/gate/gate.json --pattern llvmpipe --factor 5 --min-ms 10
    python3 scripts/update_budgets.py a1.json --pattern "NVIDIA H200"      # cavity_bench JSON, repetitions
    python3 scripts/update_budgets.py g1.json g2.json g3.json --pattern "NVIDIA H200" --factor 1.5

From cavity_bench JSON (--benchmark_repetitions=N, N >= 5), each pass's
budget is its median over the repetitions plus a margin derived from the
measured noise: max(--min-margin, --noise-factor x the repetition CV), and at
least --min-abs-ms (a GL timestamp moves in steps of its timer, and a short
pass's margin must hold at least one step).
On the H200 the repetition CV is small enough that --min-margin decides, so a
pass that is several margins slower fails clearly while an unchanged run must
move --noise-factor standard deviations to fail (study
2026-12-01_h200_budget_check).

Every pass of every configuration in gate.json gets budget = factor x its
measured median (the largest over the runs, when several gate.json files are
given), under the device class `pattern` (a substring of the device
name, as budgets.json matches it). Other device classes are kept as they are.
A CPU renderer's times swing with machine load (CI runs tests two at a time),
hence the generous default factor; on a GPU use 1.2 to 1.5.
"""
import argparse
import json
import math
import os
import re
import statistics
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "charts"))
import cavity_json  # noqa: E402  scripts/charts/cavity_json.py: plain or gzip (X.json.gz)


def from_bench(doc, a):
    """Budgets from the repetitions of a cavity_bench run: median + noise-derived margin."""
    suffix = re.compile(r"(/[a-z_]+:[^/]*|/manual_time|/real_time)+$")
    values = {}
    for b in doc["benchmarks"]:
        if b.get("run_type") != "iteration" or "@" in b["name"] or b.get("error_occurred"):
            continue
        if not b.get("label", "").startswith("clock=gpu-timestamp"):
            continue   # a wall-clock time is no budget for a GPU
        cid = suffix.sub("", b["run_name"])
        for k, v in b.items():
            if k.startswith("pass_") and k.endswith("_ms"):
                values.setdefault(cid, {}).setdefault(k[5:-3], []).append(v)
    table, widest = {}, 0.0
    for cid, passes in values.items():
        for p, v in passes.items():
            if len(v) < 5:
                sys.exit(f"update_budgets: {cid} {p}: {len(v)} repetitions; need --benchmark_repetitions=5 or more")
            m = statistics.median(v)
            margin = max(a.min_margin, a.noise_factor * statistics.stdev(v) / statistics.mean(v))
            widest = max(widest, margin)
            table.setdefault(cid, {})[p] = round(max(m * (1 + margin), m + a.min_abs_ms), 5)
    if widest >= 0.09:
        print(f"update_budgets: a margin of {100 * widest:.1f}%: a 10% slowdown of that pass may pass", file=sys.stderr)
    ctx = doc.get("context", {})
    note = (f"median of {len(next(iter(next(iter(values.values())).values())))} repetitions + "
            f"max({100 * a.min_margin:g}%, {a.noise_factor:g} x repetition CV), at least {a.min_abs_ms} ms, "
            f"from cavity_bench on {ctx.get('cavity_device', '?')} ({ctx.get('cavity_timing_mode', '?')} timing, "
            f"{ctx.get('date', '?')})")
    return table, note


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gate_json", nargs="+")
    ap.add_argument("--pattern", required=True, help="device-class substring, e.g. llvmpipe or NVIDIA")
    ap.add_argument("--factor", type=float, default=5.0)
    ap.add_argument("--min-ms", type=float, default=0.0,
                    help="floor for every budget: a 0.5 ms pass on a loaded 2-core CPU renderer can take 3 ms")
    ap.add_argument("--noise-factor", type=float, default=5.0, help="benchmark JSON: margin in repetition CVs")
    ap.add_argument("--min-margin", type=float, default=0.03, help="benchmark JSON: smallest relative margin")
    ap.add_argument("--min-abs-ms", type=float, default=0.0005, help="benchmark JSON: smallest margin in ms")
    ap.add_argument("--budgets", default=os.path.join(os.path.dirname(__file__), "..", "baselines", "budgets.json"))
    a = ap.parse_args()
    if not math.isfinite(a.factor) or a.factor <= 1:
        sys.exit(f"update_budgets: --factor {a.factor}: must be a finite number > 1")
    for flag in ("min_ms", "noise_factor", "min_margin", "min_abs_ms"):
        v = getattr(a, flag)
        if not math.isfinite(v) or v < 0:
            sys.exit(f"update_budgets: --{flag.replace('_', '-')} {v}: must be a finite number >= 0")
    try:
        runs = [cavity_json.load(p) for p in a.gate_json]
        budgets = json.load(open(a.budgets))
    except (OSError, ValueError) as e:
        sys.exit(f"update_budgets: {e}")
    if len(runs) == 1 and "benchmarks" in runs[0]:
        table, note = from_bench(runs[0], a)
    elif all(g.get("schema") == "cavity.gate/1" for g in runs):
        medians = {}
        devices = set()
        try:
            for gate in runs:
                for r in gate["results"]:
                    if r["error"]:
                        continue
                    devices.add(r["device"])
                    for t in r["timings"]:
                        key = (r["id"], t["pass"])
                        medians[key] = max(medians.get(key, 0.0), float(t["median_ms"]))
        except (KeyError, TypeError, ValueError) as e:
            sys.exit(f"update_budgets: {' '.join(a.gate_json)}: not a whole cavity gate.json ({type(e).__name__}: {e})")
        table = {}
        for (cid, pass_), m in medians.items():
            table.setdefault(cid, {})[pass_] = round(max(a.factor * m, a.min_ms), 4)
        note = (f"max({a.factor}x the largest median, {a.min_ms} ms) over {len(runs)} gate runs on "
                f"{', '.join(sorted(devices))}")
    else:
        sys.exit(f"update_budgets: {' '.join(a.gate_json)}: one cavity_bench JSON, or cavity gate.json files")
    # The configurations this run did not measure keep their budgets.
    kept = next((d.get("budgets_ms", {}) for d in budgets.get("devices", []) if d.get("pattern") == a.pattern), {})
    table = {**kept, **table}
    entry = {"pattern": a.pattern, "note": note, "budgets_ms": dict(sorted(table.items()))}
    budgets["devices"] = [d for d in budgets.get("devices", []) if d["pattern"] != a.pattern] + [entry]
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(a.budgets)))
    with os.fdopen(fd, "w") as f:
        json.dump(budgets, f, indent=1)
        f.write("\n")
    os.replace(tmp, a.budgets)
    print(f"update_budgets: {len(table)} configurations for '{a.pattern}' in {a.budgets}")


if __name__ == "__main__":
    main()
