#!/usr/bin/env python3
"""The survivors of mutants.py (and those of files its selection never
compiled) gated again on whole stored matrices (both
APIs, both stages): which of them no stored CPU matrix sees.

    survivors.py SOURCE_DIR BUILD_DIR MUTANTS_DIR [--matrices ci,gpu-cpu]

Appends to MUTANTS_DIR/survivors.jsonl a line per survivor and matrix: its
exit (1 killed) and the failing configurations."""
import argparse
import json
import os
import subprocess
import time

ap = argparse.ArgumentParser()
ap.add_argument("source")
ap.add_argument("build")
ap.add_argument("dir")
ap.add_argument("--matrices", default="ci,gpu-cpu")
a = ap.parse_args()
cavity = os.path.join(a.build, "harness", "cavity")
env = dict(os.environ, CAVITY_STORE=os.path.join(a.dir, "no-store-here"))
rows = [json.loads(l) for l in open(os.path.join(a.dir, "results.jsonl"))]
with open(os.path.join(a.dir, "survivors.jsonl"), "a") as log:
    for r in rows:
        # survivors, and mutants of files no configuration of the first
        # selection compiled
        if r["exit"] != 0 and "no configuration" not in r.get("why", ""):
            continue
        for m in a.matrices.split(","):
            out = os.path.join(a.dir, "gate-" + m)
            t = time.time()
            g = subprocess.run([cavity, "gate", "--matrix", m, "--retries", "0", "--quiet", "--kernel-source",
                                f"{r['file']}={os.path.join(a.dir, r['mutant'])}", "--out", out],
                               capture_output=True, text=True, env=env, cwd=a.source)
            failed = []
            if g.returncode == 1:
                failed = [x["id"] for x in json.load(open(os.path.join(out, "gate.json")))["results"]
                          if x["verdict"] == "fail"]
            row = {"mutant": r["mutant"], "matrix": m, "exit": g.returncode, "failed": len(failed),
                   "first_failed": failed[:3], "seconds": round(time.time() - t, 1)}
            log.write(json.dumps(row) + "\n")
            log.flush()
            print(r["mutant"], r["file"], r["line"], r["op"], m, "exit", g.returncode, "failed", len(failed),
                  row["seconds"], "s", flush=True)
            if g.returncode == 1:
                break
