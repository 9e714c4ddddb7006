"""The targets' table from targets.json (cavity_bench JSON, 10 interleaved
repetitions): medians of the repetitions, ms, Vulkan and GL, the default
(exact=0) beside exact=1.   python3 table.py targets.json"""
import collections
import json
import statistics
import sys

runs = json.load(open(sys.argv[1]))
vals = collections.defaultdict(list)
for b in runs["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    cid = b.get("run_name", b["name"]).split("/iterations")[0]
    passes = {k[5:-3]: v for k, v in b.items() if k.startswith("pass_") and k.endswith("_ms")}
    for k, v in passes.items():
        vals[(cid, k)].append(v)
    vals[(cid, "pipeline")].append(sum(v for k, v in passes.items() if k != "gbuffer"))
med = {k: statistics.median(v) for k, v in vals.items()}


def cfg(kernel="alchemy_fast", n=16, variant="", res="full", api="vk"):
    return f"corner/{kernel}/n{n}/b4/{variant}{res}/1920x1080/{api}/compute"


rows = [
    ("alchemy_fast n16 AO", dict(), "ao", "0.09 / 0.095"),
    ("alchemy_fast n32 AO", dict(n=32), "ao", "0.17"),
    ("hemisphere_fast n16 AO", dict(kernel="hemisphere_fast"), "ao", "0.17"),
    ("hemisphere_fast n32 AO", dict(kernel="hemisphere_fast", n=32), "ao", ""),
    ("pyramid", dict(), "pyramid", "0.02"),
    ("alchemy_fast n16 b4 pipeline", dict(), "pipeline", "0.22"),
    ("half pipeline", dict(res="half"), "pipeline", ""),
    ("half pipeline, fused tail", dict(res="half", variant="fused_tail=1/"), "pipeline", ""),
]
print("| figure | target | default (exact=0) VK / GL | exact=1 VK / GL | GL over VK (default) |")
print("| --- | ---: | ---: | ---: | ---: |")
for name, kw, p, target in rows:
    d = [med.get((cfg(api=a, **kw), p)) for a in ("vk", "gl")]
    ekw = dict(kw)
    if ekw.get("variant") != "fused_tail=1/":
        ekw["variant"] = "exact=1/"
    e = [med.get((cfg(api=a, **ekw), p)) for a in ("vk", "gl")] if ekw.get("variant") == "exact=1/" else [None, None]
    fmt = lambda x: "-" if x is None else f"{x:.4f}"
    print(f"| {name} | {target} | {fmt(d[0])} / {fmt(d[1])} | {fmt(e[0])} / {fmt(e[1])} | {d[1] / d[0] - 1:+.1%} |")
for api in ("vk", "gl"):
    full = med[(cfg(api=api), "pipeline")]
    print(f"half over full, {api}: {full / med[(cfg(api=api, res='half'), 'pipeline')]:.2f}x, "
          f"fused {full / med[(cfg(api=api, res='half', variant='fused_tail=1/'), 'pipeline')]:.2f}x")
print()
print("every pass, ms: VK / GL")
for c in sorted({c for c, _ in med}):
    if "/vk/" not in c or "@" in c:
        continue
    g = c.replace("/vk/", "/gl/")
    ps = sorted({p for cc, p in med if cc == c})
    print(c.replace("/vk/compute", ""), ", ".join(f"{p} {med[(c, p)]:.4f}/{med.get((g, p), float('nan')):.4f}" for p in ps))
