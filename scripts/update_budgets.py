#!/usr/bin/env python3
"""Writes timing budgets into baselines/budgets.json from a gate run.

    python3 scripts/update_budgets.py out/gate/gate.json --pattern llvmpipe --factor 5 --min-ms 10

Every pass of every configuration in gate.json gets budget = factor x its
measured median, under the device class `pattern` (a substring of the device
name, as budgets.json matches it). Other device classes are kept as they are.
A CPU renderer's times swing with machine load (CI runs tests two at a time),
hence the generous default factor; on a GPU use 1.2 to 1.5.
"""
import argparse
import json
import os
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("gate_json")
    ap.add_argument("--pattern", required=True, help="device-class substring, e.g. llvmpipe or NVIDIA")
    ap.add_argument("--factor", type=float, default=5.0)
    ap.add_argument("--min-ms", type=float, default=0.0,
                    help="floor for every budget: a 0.5 ms pass on a loaded 2-core CPU renderer can take 3 ms")
    ap.add_argument("--budgets", default=os.path.join(os.path.dirname(__file__), "..", "baselines", "budgets.json"))
    a = ap.parse_args()
    if a.factor <= 1:
        sys.exit(f"update_budgets: --factor {a.factor}: must be > 1")
    try:
        gate = json.load(open(a.gate_json))
        budgets = json.load(open(a.budgets))
    except (OSError, json.JSONDecodeError) as e:
        sys.exit(f"update_budgets: {e}")
    if gate.get("schema") != "cavity.gate/1":
        sys.exit(f"update_budgets: {a.gate_json}: not a cavity gate.json")
    table = {}
    devices = set()
    for r in gate["results"]:
        if r["error"]:
            continue
        devices.add(r["device"])
        table[r["id"]] = {t["pass"]: round(max(a.factor * t["median_ms"], a.min_ms), 4) for t in r["timings"]}
    entry = {"pattern": a.pattern,
             "note": f"max({a.factor}x the median, {a.min_ms} ms) from a gate run on {', '.join(sorted(devices))}",
             "budgets_ms": dict(sorted(table.items()))}
    budgets["devices"] = [d for d in budgets.get("devices", []) if d["pattern"] != a.pattern] + [entry]
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(os.path.abspath(a.budgets)))
    with os.fdopen(fd, "w") as f:
        json.dump(budgets, f, indent=1)
        f.write("\n")
    os.replace(tmp, a.budgets)
    print(f"update_budgets: {len(table)} configurations for '{a.pattern}' in {a.budgets}")


if __name__ == "__main__":
    main()
