#!/usr/bin/env python3
"""The tables of README.md from the tarballs beside this file.

    python3 lab/2026-12-03_h200_overheads/table.py

probes: median over the processes of each probe's median_us counter;
chain and tile: median over every repetition of each pass's median (ms);
fp16 and lean: median over the rounds of cavity_render's per-pass medians.
"""
import glob
import io
import json
import os
import statistics as st
import tarfile

HERE = os.path.dirname(os.path.abspath(__file__))


def members(tgz):
    with tarfile.open(os.path.join(HERE, tgz)) as t:
        for m in t.getmembers():
            if m.isfile():
                yield m.name.lstrip("./"), t.extractfile(m).read()


def bench_passes(files, prefix):
    out = {}
    for name, data in files:
        if not (name.startswith(prefix + ".r") and name.endswith(".json")):
            continue
        for b in json.loads(data.replace(b": NaN", b": null"))["benchmarks"]:
            if b.get("run_type") != "iteration" or "@" in b["name"]:
                continue
            cid = b["name"].split("/iterations")[0]
            out.setdefault((cid, "pipeline"), []).append(b["real_time"])
            for k, v in b.items():
                if k.startswith("pass_") and k.endswith("_ms") and k != "pass_gbuffer_ms":
                    out.setdefault((cid, k[5:-3]), []).append(v)
    return out


def probes(files):
    rows = {}
    for name, data in files:
        if name.startswith("probes_") and name.endswith(".json"):
            mode = name.split("_")[1].split(".")[0]
            for b in json.loads(data)["benchmarks"]:
                rows.setdefault((b["name"].split("/iterations")[0], mode), []).append(b["median_us"])
    print("probe                                  narrow   full   none   (us a pass, medians of processes)")
    for probe in sorted({k[0] for k in rows}):
        cells = [f"{st.median(rows[(probe, m)]):6.2f}" for m in ("narrow", "full", "none")]
        print(f"{probe:38s} " + " ".join(cells))


def compare(a, b, names):
    for k in sorted(a):
        if k in b:
            x, y = st.median(a[k]), st.median(b[k])
            print(f"{k[0]:56s} {k[1]:20s} {names[0]} {x:.4f} {names[1]} {y:.4f} {100 * (y / x - 1):+5.1f}%")


def renders(files, variants):
    res = {}
    for name, data in files:
        if name.endswith("manifest.json") and name.split(".r")[0] in variants:
            v = name.split(".r")[0]
            for c in json.loads(data)["configurations"]:
                for r in c["renders"]:
                    for t in r["timings"]:
                        res.setdefault((c["api"], t["pass"], v), []).append(t["median_ms"])
                    res.setdefault((c["api"], "digests", v), set()).add(" ".join(i["digest"][-8:] for i in r["images"]))
    return res


def main():
    pc = list(members("overheads_probes_chain.tgz"))
    probes(pc)
    print("\nalchemy_fast n16 b4, barriers narrow against none (ms):")
    compare(bench_passes(pc, "chain_narrow"), bench_passes(pc, "chain_none"), ("narrow", "none"))
    tf = list(members("overheads_tile_fp16.tgz"))
    print("\ntiles: one pixel an invocation against the upsamples' 2x2 and 2x2 everywhere (ms):")
    single = bench_passes(tf, "tile_1x1")
    compare(single, bench_passes(tf, "tile_own"), ("1x1", "own"))
    compare(single, bench_passes(tf, "tile_2x2"), ("1x1", "2x2"))
    print("\nhalf floats (both --exact 0), cavity_render, ms:")
    r = renders(tf, ("render_inexact", "render_fp16"))
    for api in ("gl", "vk"):
        for p in ("ao", "blur_x", "blur_y", "composite"):
            a, b = st.median(r[(api, p, "render_inexact")]), st.median(r[(api, p, "render_fp16")])
            print(f"{api} {p:10s} float {a:.4f} half {b:.4f} {100 * (b / a - 1):+5.1f}%")
    print("\nleaner integer work (the same bits), cavity_render, AO pass, ms:")
    names = ("a_committed", "a_lean", "a_pyr", "a_nosource", "h_committed", "h_pyr")
    r = renders(list(members("lean.tgz")), names)
    for api in ("gl", "vk"):
        for v in names:
            base = st.median(r[(api, "ao", v[0] + "_committed")])
            m = st.median(r[(api, "ao", v)])
            print(f"{api} {v:12s} {m:.4f} ({100 * (m / base - 1):+5.1f}%)  digests {sorted(r[(api, 'digests', v)])}")
    print("\nthe pyramidTexel form (new) against c096d07 (old), cavity_render, AO pass, ms:")
    files = [(n.replace(".alchemy_fast.", "_a.").replace(".hemisphere_fast.", "_h."), d) for n, d in members("ab_call.tgz")]
    names = ("new_a", "old_a", "new_h", "old_h")
    r = {}
    for name, data in files:
        if name.endswith("manifest.json") and name.split(".r")[0] in names:
            for c in json.loads(data)["configurations"]:
                for rr in c["renders"]:
                    for t in rr["timings"]:
                        r.setdefault((c["id"], t["pass"], name.split(".r")[0]), []).append(t["median_ms"])
    for (cid, p, v) in sorted(r):
        if p == "ao" and v.startswith("new"):
            a, b = st.median(r[(cid, p, "old" + v[3:])]), st.median(r[(cid, p, v)])
            print(f"{cid:56s} old {a:.4f} new {b:.4f} {100 * (b / a - 1):+5.1f}%")

main()
