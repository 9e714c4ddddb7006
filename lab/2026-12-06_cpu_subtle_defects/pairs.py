#!/usr/bin/env python3
"""Every candidate metric (candidates.py) for every image of render folder
NEW that differs from the same configuration's image in render folder REF,
one JSON line each. With `glcompute`, each configuration is compared with
REF's GL compute render of it instead (the CPU renderers' cross-API noise).
Images a folder holds only as an approved digest are read from the image
store (STORE, default the checkout's baselines/store).

    pairs.py NEW REF LABEL [glcompute] > lines.jsonl
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import candidates  # noqa: E402
import f32z  # noqa: E402

STORE = os.environ.get("STORE", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "baselines", "store"))


def images(folder):
    out = {}
    for c in json.load(open(os.path.join(folder, "manifest.json")))["configurations"]:
        for im in c["renders"][0]["images"]:
            f = os.path.join(folder, im["file"]) if im.get("file") else None
            if not f or not os.path.exists(f):
                alg, hx = im["digest"].split(":")
                f = os.path.join(STORE, alg, hx + ".f32z")
                f = f if os.path.exists(f) else None
            out[(c["id"], im["name"])] = (im["digest"], f)
    return out


def luminance(path):
    w, h, c, px = f32z.read(path)
    return w, h, candidates.lum(w, h, c, px)


def main():
    new, ref, label = sys.argv[1:4]
    to_gl = len(sys.argv) > 4 and sys.argv[4] == "glcompute"
    a, b = images(new), images(ref)
    for (cid, name), (digest, f) in sorted(a.items()):
        key = ("/".join(cid.split("/")[:-2] + ["gl", "compute"]) if to_gl else cid, name)
        if key not in b or b[key][0] == digest:
            continue
        if not f or not b[key][1]:
            print(json.dumps({"label": label, "id": cid, "image": name, "missing": True}))
            continue
        w, h, x = luminance(f)
        _, _, y = luminance(b[key][1])
        blurred = b.get((key[0], "ao_blur"), (None, None))[1]
        m = candidates.metrics(w, h, x, y, luminance(blurred)[2] if blurred else None)
        m.update(label=label, id=cid, image=name)
        print(json.dumps(m), flush=True)


if __name__ == "__main__":
    main()
