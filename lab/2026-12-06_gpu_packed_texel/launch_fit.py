"""The floor's launch term fitted to the empty dispatch: from a cavity_bench
JSON with the timer/ probes (10 repetitions), per API the median of each
timer/empty_chain/<WxH> against its workgroups, a least-squares line
fixed_us + per_workgroup_ns x workgroups; and the one-scope chain beside
the per-pass one (what a pass's own timestamps cost).
    python3 launch_fit.py targets.json[.gz]"""
import collections
import gzip
import json
import statistics
import sys

path = sys.argv[1]
runs = json.load(gzip.open(path) if path.endswith(".gz") else open(path))
us, groups = collections.defaultdict(list), {}
for b in runs["benchmarks"]:
    name = b.get("run_name", b["name"]).split("/iterations")[0]
    if not name.startswith("timer/") or b.get("run_type") != "iteration":
        continue
    us[name].append(b["median_us"])
    if "workgroups" in b:
        groups[name] = b["workgroups"]
med = {k: statistics.median(v) for k, v in us.items()}
print("| probe | workgroups | median us (of %d) |" % max(len(v) for v in us.values()))
print("| --- | ---: | ---: |")
for k in sorted(med):
    print(f"| `{k}` | {groups.get(k, '')} | {med[k]:.2f} |")
for api in ("vk", "gl"):
    pts = [(groups[k], med[k]) for k in med if k.startswith("timer/empty_chain/") and k.endswith("/" + api) and k in groups]
    if len(pts) < 2:
        continue
    mx, my = statistics.mean(x for x, _ in pts), statistics.mean(y for _, y in pts)
    slope = sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)
    fixed = my - slope * mx
    worst = max(abs(fixed + slope * x - y) for x, y in pts)
    print(f"{api}: launch = {fixed:.2f} us + {slope * 1000:.3f} ns x workgroups ({len(pts)} sizes, worst residual {worst:.2f} us)")
