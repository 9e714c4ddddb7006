"""Every pass of the targets' configurations against its floor, from
cavity_bench JSON (10 interleaved repetitions): medians of the repetitions,
ms, Vulkan / GL, the floor the run computed (floor_<pass>_ms, the same on
both APIs) and measured / floor; then each pipeline's sum of floors, and
half over full at the floors.   python3 floors.py targets.json"""
import collections
import json
import statistics
import sys

runs = json.load(open(sys.argv[1]))
vals, floors = collections.defaultdict(list), {}
for b in runs["benchmarks"]:
    if b.get("run_type") != "iteration":
        continue
    cid = b.get("run_name", b["name"]).split("/iterations")[0]
    for k, v in b.items():
        if k.startswith("pass_") and k.endswith("_ms"):
            vals[(cid, k[5:-3])].append(v)
        elif k.startswith("floor_") and k.endswith("_ms"):
            floors[(cid, k[6:-3])] = v
med = {k: statistics.median(v) for k, v in vals.items()}

print("| configuration (corner, b4, 1920x1080, compute) | pass | floor | Vulkan | GL | Vulkan / floor | GL / floor |")
print("| --- | --- | ---: | ---: | ---: | ---: | ---: |")
sums = {}
for c in sorted({c for c, _ in med if "/vk/" in c}):
    g = c.replace("/vk/", "/gl/")
    name = c.replace("corner/", "").replace("/b4", "").replace("/1920x1080/vk/compute", "")
    tot = [0.0, 0.0, 0.0]
    for p in sorted({p for cc, p in med if cc == c}):
        if p == "gbuffer":
            continue
        f, v, l = floors.get((c, p)), med[(c, p)], med.get((g, p), float("nan"))
        tot = [tot[0] + (f or 0), tot[1] + v, tot[2] + l]
        r = lambda x: "-" if not f else f"{x / f:.2f}x"
        print(f"| {name} | {p} | {f or 0:.4f} | {v:.4f} | {l:.4f} | {r(v)} | {r(l)} |")
    print(f"| {name} | **pipeline** | **{tot[0]:.4f}** | **{tot[1]:.4f}** | **{tot[2]:.4f}** | "
          f"{tot[1] / tot[0]:.2f}x | {tot[2] / tot[0]:.2f}x |")
    sums[name] = tot
print()
for k in ("alchemy_fast", "hemisphere_fast"):
    full, half = sums.get(f"{k}/n16/full"), sums.get(f"{k}/n16/fused_tail=1/half")
    if full and half:
        print(f"{k} n16, half (fused tail) over full: at the floors {full[0] / half[0]:.2f}x, "
              f"measured {full[1] / half[1]:.2f}x (Vulkan) / {full[2] / half[2]:.2f}x (GL)")
