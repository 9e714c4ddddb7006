"""Largest MAE change between two runs of quality.sh, per size, from their
quality.json files:  python3 quality_delta.py before after"""
import json
import sys

a, b = sys.argv[1:3]
for size in ("320x180", "640x360"):
    rows = [json.load(open(f"/tmp/q_{size}_{n}/quality.json"))["rows"] for n in (a, b)]
    mae = [{(r["scene"], r["kernel"], r["samples"]): r["mae"] for r in rs} for rs in rows]
    worst = max(mae[0], key=lambda k: abs(mae[1][k] - mae[0][k]))
    print(f"{size}: largest |MAE change| {abs(mae[1][worst] - mae[0][worst]):.2g} at {'/'.join(map(str, worst))}")
