"""Pairs each fused_blur=1 configuration of a render manifest with the same
configuration without it, and says per image whether the digests agree."""
import json, sys
m = json.load(open(sys.argv[1]))
dig = {}
for c in m["configurations"]:
    r = c["renders"][0]
    dig[c["id"]] = {i["name"]: i["digest"] for i in r["images"]}
same = diff = 0
for cid, imgs in sorted(dig.items()):
    if "fused_blur=1/" not in cid: continue
    base = dig.get(cid.replace("fused_blur=1/", ""))
    if base is None: print("no pair:", cid); continue
    moved = [n for n in ("ao", "ao_blur", "color") if imgs.get(n) != base.get(n)]
    print(("SAME " if not moved else "DIFF ") + cid + ("" if not moved else "  moved: " + ",".join(moved)))
    same += not moved; diff += bool(moved)
print(f"{same} pairs the same bits, {diff} differ")
