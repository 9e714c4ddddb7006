#!/usr/bin/env python3
"""Lists the configurations of a render folder's manifest.json that
`baselines approve` leaves out: a render error, or repetitions whose images
differ, with the error's text.
   errors.py RENDER_DIR"""
import json, sys, collections

m = json.load(open(sys.argv[1] + "/manifest.json"))
left, causes = [], collections.Counter()
for c in m["configurations"]:
    errs = [r.get("error", "") for r in c.get("renders", []) if r.get("error")]
    digests = collections.defaultdict(set)
    for r in c.get("renders", []):
        for i in r.get("images", []):
            digests[i["name"]].add(i.get("digest"))
    if errs:
        left.append(f"{c['id']}: error: {errs[0][:300]}")
        causes[errs[0][:80]] += 1
    elif any(len(d) > 1 for d in digests.values()):
        left.append(f"{c['id']}: repetitions differ: {sorted(k for k, d in digests.items() if len(d) > 1)}")
        causes["repetitions differ"] += 1
    elif not digests:
        left.append(f"{c['id']}: no image")
        causes["no image"] += 1
print(f"{len(m['configurations'])} configurations, {len(left)} left out")
for k, n in causes.most_common():
    print(f"  {n:4d}  {k}")
for line in left:
    print(line)
