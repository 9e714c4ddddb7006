#!/usr/bin/env python3
"""Whether every image of the render manifests given is approved for the
class it was rendered on (baselines/approvals.json), per matrix: the
configurations whose digests are all approved, and the first few that are
not (a render whose two frames differed is never approved).
    check_digests.py APPROVALS_JSON MANIFEST.json.gz...
"""
import gzip
import json
import re
import sys


def device_class(name):
    """harness/plan/approvals.cpp's deviceClass: the name up to ' (' or '/', lower case, '-' between words."""
    cut = min([i for i in (name.find(" ("), name.find("/")) if i >= 0] or [len(name)])
    return re.sub(r"-+", "-", re.sub(r"[^a-z0-9]", "-", name[:cut].lower())).strip("-") or "unknown"


def main():
    approvals = json.load(open(sys.argv[1]))["approvals"]
    ok = {(a["device_class"], a["key"], a["api"], a["stage"], a["image"], a["digest"])
          for a in approvals if a["verdict"] == "positive"}
    for path in sys.argv[2:]:
        doc = json.load(gzip.open(path))
        total, missing = 0, []
        for c in doc["configurations"]:
            total += 1
            cls, stage = device_class(c["device"]), c["id"].rsplit("/", 1)[1]
            for r in c["renders"]:
                for i in r["images"]:
                    if (cls, c["baseline_key"], c["api"], stage, i["name"], i["digest"]) not in ok:
                        missing.append(c["id"] + ("" if r.get("deterministic", True) else " (frames differed)"))
        ids = sorted(set(missing))
        print(f"{path}: {total - len(ids)} of {total} configurations approved by digest; not: {ids[:6]}")


if __name__ == "__main__":
    main()
