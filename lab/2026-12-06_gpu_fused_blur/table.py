"""The pair against the fused blur, from a cavity_bench JSON of repetitions:
per configuration and API, the blur passes' medians (blur_x + blur_y, or
blur), the pipeline's (the sum of its passes' scopes) and the one-scope
pipeline's, ms.   python3 table.py fused.json[.gz]"""
import collections
import gzip
import json
import statistics
import sys

path = sys.argv[1]
runs = json.load(gzip.open(path) if path.endswith(".gz") else open(path))
vals = collections.defaultdict(list)
for b in runs["benchmarks"]:
    if b.get("run_type") != "iteration" or "@" in b["name"]:
        continue
    cid = b.get("run_name", b["name"]).split("/iterations")[0]
    blur = sum(b.get(f"pass_{p}_ms", 0.0) for p in ("blur_x", "blur_y", "blur"))
    vals[(cid, "blur")].append(blur)
    vals[(cid, "pipeline")].append(b["real_time"])
    if "pipeline_one_scope_ms" in b:
        vals[(cid, "one")].append(b["pipeline_one_scope_ms"])
med = {k: statistics.median(v) for k, v in vals.items()}
print("| configuration (corner, n16, b4, 1920x1080, compute) | API | blur: pair / fused | pipeline: pair / fused | change | one scope: pair / fused |")
print("| --- | --- | ---: | ---: | ---: | ---: |")
for cid in sorted({c for c, _ in med if "fused_blur" not in c}):
    fused = cid.replace("/b4/", "/b4/fused_blur=1/")
    if (fused, "blur") not in med:
        continue
    api = "Vulkan" if "/vk/" in cid else "GL"
    name = cid.replace("corner/", "").replace("/n16/b4", "").split("/1920x1080")[0]
    p0, p1 = med[(cid, "pipeline")], med[(fused, "pipeline")]
    o0, o1 = med.get((cid, "one"), float("nan")), med.get((fused, "one"), float("nan"))
    print(f"| {name} | {api} | {med[(cid, 'blur')]:.4f} / {med[(fused, 'blur')]:.4f} | {p0:.4f} / {p1:.4f} | "
          f"{100 * (p1 / p0 - 1):+.1f}% | {o0:.4f} / {o1:.4f} |")
