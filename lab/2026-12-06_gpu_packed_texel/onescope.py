"""GL against Vulkan two ways, from a cavity_bench JSON of repetitions:
the pipeline as the sum of its passes' scopes (the benchmark's time) and
as one scope (pipeline_one_scope_ms), medians, ms.
    python3 onescope.py onescope.json[.gz]"""
import collections
import gzip
import json
import statistics
import sys

path = sys.argv[1]
runs = json.load(gzip.open(path) if path.endswith(".gz") else open(path))
summed, one = collections.defaultdict(list), collections.defaultdict(list)
for b in runs["benchmarks"]:
    if b.get("run_type") != "iteration" or "@" in b["name"]:
        continue
    cid = b.get("run_name", b["name"]).split("/iterations")[0]
    summed[cid].append(b["real_time"])
    if "pipeline_one_scope_ms" in b:
        one[cid].append(b["pipeline_one_scope_ms"])
med = lambda xs: statistics.median(xs) if xs else float("nan")
print("| configuration (corner, b4, 1920x1080, compute) | passes' scopes Vulkan / GL | GL / Vulkan | one scope Vulkan / GL | GL / Vulkan |")
print("| --- | ---: | ---: | ---: | ---: |")
for vk in sorted(c for c in summed if "/vk/" in c):
    gl = vk.replace("/vk/", "/gl/")
    name = vk.replace("corner/", "").replace("/b4", "").replace("/1920x1080/vk/compute", "")
    s_vk, s_gl, o_vk, o_gl = med(summed[vk]), med(summed[gl]), med(one[vk]), med(one[gl])
    print(f"| {name} | {s_vk:.4f} / {s_gl:.4f} | {s_gl / s_vk:.3f} | {o_vk:.4f} / {o_gl:.4f} | {o_gl / o_vk:.3f} |")
