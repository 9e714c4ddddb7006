"""The separable blur as two passes against one (fused_blur=1), from a
cavity_bench JSON of interleaved repetitions: medians, ms, Vulkan / GL.
    python3 table.py targets.json[.gz]"""
import collections
import gzip
import json
import statistics
import sys

opener = gzip.open if sys.argv[1].endswith(".gz") else open
runs = json.load(opener(sys.argv[1], "rt"))
vals = collections.defaultdict(list)
for b in runs["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    cid = b.get("run_name", b["name"]).split("/iterations")[0]
    passes = {k[5:-3]: v for k, v in b.items() if k.startswith("pass_") and k.endswith("_ms")}
    for k, v in passes.items():
        vals[(cid, k)].append(v)
    vals[(cid, "pipeline")].append(sum(v for k, v in passes.items() if k != "gbuffer"))
    vals[(cid, "blur")].append(sum(v for k, v in passes.items() if k.startswith("blur")))
med = {k: statistics.median(v) for k, v in vals.items()}


def cid(kernel, n, variant, res, api, fused):
    return f"corner/{kernel}/n{n}/b4/{'fused_blur=1/' if fused else ''}{variant}{res}/1920x1080/{api}/compute"


def pair(kernel, n, variant, res, what, fused):
    return [med.get((cid(kernel, n, variant, res, a, fused), what)) for a in ("vk", "gl")]


fmt = lambda x: "-" if x is None else f"{x:.4f}"
print("| configuration | what | two passes, VK / GL | one pass, VK / GL | change, VK / GL |")
print("| --- | --- | ---: | ---: | ---: |")
rows = [(k, n, v, r) for k in ("alchemy_fast", "hemisphere_fast") for n, v, r in
        ((16, "", "full"), (32, "", "full"), (16, "", "half"), (16, "fused_tail=1/", "half"))]
for k, n, v, r in rows:
    for what in ("blur", "pipeline"):
        a, b = pair(k, n, v, r, what, False), pair(k, n, v, r, what, True)
        if None in a or None in b:
            continue
        ch = " / ".join(f"{y / x - 1:+.1%}" for x, y in zip(a, b))
        print(f"| {k} n{n} {v}{r} | {what} | {fmt(a[0])} / {fmt(a[1])} | {fmt(b[0])} / {fmt(b[1])} | {ch} |")
print()
for api in ("vk", "gl"):
    for fused in (False, True):
        full = med.get((cid("alchemy_fast", 16, "", "full", api, fused), "pipeline"))
        half = med.get((cid("alchemy_fast", 16, "", "half", api, fused), "pipeline"))
        tail = med.get((cid("alchemy_fast", 16, "fused_tail=1/", "half", api, fused), "pipeline"))
        if full and half and tail:
            print(f"alchemy_fast n16 b4 {api} {'one blur pass' if fused else 'two blur passes'}: full {full:.4f}, "
                  f"half {half:.4f} ({full / half:.2f}x), half with the fused tail {tail:.4f} ({full / tail:.2f}x)")
