#!/usr/bin/env python3
"""Drops the approvals that the half-resolution depth change made stale:
positive approvals of the half-resolution configurations of the kernels that
read the pyramid (alchemy_fast, hemisphere_fast), made before CUTOFF, whose
digest no current render gives. Kept, they would pass a render of the old
shader (a revert of the change) as approved on their device class. The
current digests are those of the gate or render folders given (gate.json or
manifest.json); classes with no folder given lose every stale approval and
are judged by tolerance until their card renders them again.

    drop_stale.py APPROVALS_JSON CUTOFF_ISO FOLDER...
"""
import json
import os
import re
import sys

KEYS = re.compile(r"^[a-z]+/(alchemy_fast|hemisphere_fast)/.*/half/")


def current_digests(folder):
    out = set()
    g = os.path.join(folder, "gate.json")
    if os.path.exists(g):
        for r in json.load(open(g))["results"]:
            out |= {i["digest"] for i in r["images"]}
    m = os.path.join(folder, "manifest.json")
    if os.path.exists(m):
        for r in json.load(open(m))["renders"]:
            out |= set(r.get("digests", {}).values())
    return out


def main():
    path, cutoff, folders = sys.argv[1], sys.argv[2], sys.argv[3:]
    current = set()
    for f in folders:
        current |= current_digests(f)
    doc = json.load(open(path))
    kept, dropped = [], {}
    for a in doc["approvals"]:
        stale = (a["verdict"] == "positive" and KEYS.search(a["key"]) and a["when"] < cutoff
                 and a["digest"] not in current)
        if stale:
            dropped[a["device_class"]] = dropped.get(a["device_class"], 0) + 1
        else:
            kept.append(a)
    doc["approvals"] = kept
    # The file's own layout: one approval a line, so that a change reviews
    # as the lines it adds and drops.
    lines = [json.dumps(a, separators=(",", ":"), ensure_ascii=False) for a in kept]
    with open(path + ".tmp", "w") as f:
        f.write('{\n  "schema": ' + json.dumps(doc["schema"]) + ',\n  "approvals": [\n    ')
        f.write(",\n    ".join(lines))
        f.write("\n  ]\n}\n")
    os.replace(path + ".tmp", path)
    print(f"dropped {sum(dropped.values())} stale approvals: {dropped}; {len(kept)} kept")


if __name__ == "__main__":
    main()
