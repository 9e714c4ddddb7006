#!/usr/bin/env python3
"""Records that another tool wrote, damaged or edited by hand: cavity_bench
JSON read by `compare` and `history ingest`, render manifests read by `gate
judge`, gate.json shards read by `gate merge`. Each wrong type, range or
missing part must be exit 2 with one line naming the file and the field,
with nothing written: none may abort (they once did, inside the JSON
library), be read as another value (a time unit guessed as ns), or be judged
as a smaller selection that then reads "all passed".

    damaged_records.py CAVITY CAVITY_RENDER SOURCE_DIR
"""
import copy
import json
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from baselines_copy import drop_cpu_approvals  # noqa: E402

NAME = "corner/alchemy/n16/b4/full/160x90/vk/compute/iterations:1/manual_time"


def bench_doc():
    entries = [{"name": NAME, "run_name": NAME, "run_type": "iteration", "repetitions": 4, "repetition_index": k,
                "threads": 1, "iterations": 1, "real_time": 10.0 + k / 10, "cpu_time": 1.0, "time_unit": "ms",
                "pass_ao_ms": 5.0 + k / 10, "label": "clock=gpu-timestamp"} for k in range(4)]
    return {"context": {"date": "2026-12-07T00:00:00+00:00", "cavity_software_renderer": "false"}, "benchmarks": entries}


def first(doc, key, value):
    doc["benchmarks"][0][key] = value


BENCH = {   # variant: (edit, words the one line must hold)
    "renderer-number": (lambda d: d["context"].update(cavity_software_renderer=1), ["cavity_software_renderer"]),
    "error-string": (lambda d: first(d, "error_occurred", "yes"), ["error_occurred", '"yes"']),
    "unit-number": (lambda d: first(d, "time_unit", 5), ["time_unit", "5"]),
    "unit-missing": (lambda d: d["benchmarks"][0].pop("time_unit"), ["time_unit", "missing"]),
    "pass-nan": (lambda d: first(d, "pass_ao_ms", None), ["pass_ao_ms", "null"]),
    "pass-string": (lambda d: first(d, "pass_ao_ms", "3"), ["pass_ao_ms", '"3"']),
    "time-huge": (lambda d: first(d, "real_time", 1e308), ["real_time", "1e+308"]),
    "repetition-string": (lambda d: first(d, "repetition_index", "x"), ["repetition_index", '"x"']),
    "iterations-zero": (lambda d: first(d, "iterations", 0), ["iterations", "0"]),
    "run-type-number": (lambda d: first(d, "run_type", 5), ["run_type", "5"]),
}


def manifest_drop(m, keep):
    m["configurations"] = m["configurations"][:keep]


MANIFEST = {
    "format-number": (lambda m: m.update(image_format=5), ["image_format", "5"]),
    "index-fraction": (lambda m: m["configurations"][0].update(index=0.5), ["index", "0.5"]),
    "one-left-out": (lambda m: manifest_drop(m, 1), ["entry 1", "missing"]),
    "none-left": (lambda m: manifest_drop(m, 0), ["entry 0", "missing"]),
    "width-huge": (lambda m: m["configurations"][0]["renders"][0]["images"][0].update(width=4000000000),
                   ["width", "4000000000"]),
    "median-negative": (lambda m: m["configurations"][0]["renders"][0]["timings"][0].update(median_ms=-5),
                        ["median_ms", "-5"]),
}


def main():
    cavity, render, source = sys.argv[1:4]
    failures = []

    def check(label, cmd, words, cwd, gone):
        r = subprocess.run(cmd, capture_output=True, text=True, cwd=cwd, timeout=300)
        lines = [l for l in r.stderr.splitlines() if l.strip() and not l.startswith("gate: [")]
        if r.returncode != 2 or len(lines) != 1 or not all(w in lines[0] for w in words):
            failures.append(f"{label}: exit {r.returncode}, wanted 2 and one line with {words}:\n{r.stderr}")
        if os.path.exists(os.path.join(cwd, gone)):
            failures.append(f"{label}: {gone} was written")
            shutil.rmtree(os.path.join(cwd, gone), ignore_errors=True)
            if os.path.isfile(os.path.join(cwd, gone)):
                os.remove(os.path.join(cwd, gone))

    with tempfile.TemporaryDirectory() as tmp:
        with open(os.path.join(tmp, "good.json"), "w") as f:
            json.dump(bench_doc(), f)
        for label, (edit, words) in BENCH.items():
            doc = bench_doc()
            edit(doc)
            path = os.path.join(tmp, label + ".json")
            with open(path, "w") as f:
                json.dump(doc, f)
            check("compare " + label, [cavity, "compare", "good.json", label + ".json", "--json", "out"],
                  [label + ".json"] + words, tmp, "out")
            check("ingest " + label, [cavity, "history", "ingest", "--db", "h.sqlite", "--commit", "abc1234", label + ".json"],
                  [label + ".json"] + words, tmp, "h.sqlite")

        # Two shards of the smoke matrix (one configuration each), rendered
        # and judged: the manifests and gate.json files the variants edit.
        baselines = os.path.join(source, "baselines")
        for i in (0, 1):
            subprocess.run([render, "--matrix", "smoke", "--baselines", baselines, "--shard", f"{i}/2", "--out", f"r{i}"],
                           cwd=tmp, check=True, capture_output=True, timeout=300)
            subprocess.run([cavity, "gate", "judge", f"r{i}", "--baselines", baselines, "--shards", f"{i}/2", "--out", f"s{i}",
                            "--quiet"],
                           cwd=tmp, check=True, capture_output=True, timeout=300)
        subprocess.run([render, "--matrix", "smoke", "--baselines", baselines, "--out", "r"], cwd=tmp, check=True,
                       capture_output=True, timeout=300)
        manifest = json.load(open(os.path.join(tmp, "r", "manifest.json")))
        for label, (edit, words) in MANIFEST.items():
            folder = os.path.join(tmp, "m-" + label)
            shutil.copytree(os.path.join(tmp, "r"), folder)
            m = copy.deepcopy(manifest)
            edit(m)
            with open(os.path.join(folder, "manifest.json"), "w") as f:
                json.dump(m, f)
            check("judge " + label, [cavity, "gate", "judge", "m-" + label, "--baselines", baselines, "--out", "out"],
                  words, tmp, "out")

        shard = json.load(open(os.path.join(tmp, "s1", "gate.json")))
        other = json.load(open(os.path.join(tmp, "s0", "gate.json")))
        merges = {
            "results-lost": (lambda g: g.update(results=[]), ["s1x/gate.json", "configurations"]),
            "another-shards-results": (lambda g: g.update(results=other["results"]), ["s1x", "also in s0"]),
            "another-filter": (lambda g: g.update(filter="/vk/"), ["s1x", "--filter"]),
            "verdict-bogus": (lambda g: g["results"][0].update(verdict="bogus"), ["s1x/gate.json", "verdict", "must be one of"]),
            "verdict-number": (lambda g: g["results"][0].update(verdict=3), ["s1x/gate.json", "verdict"]),
            "another-source": (lambda g: g.update(kernel_sources=[{"name": "a.glsl", "file": "/e.glsl", "digest": "sha256:0"}]),
                               ["s1x", "kernel sources"]),
        }
        for label, (edit, words) in merges.items():
            g = copy.deepcopy(shard)
            edit(g)
            shutil.rmtree(os.path.join(tmp, "s1x"), ignore_errors=True)
            shutil.copytree(os.path.join(tmp, "s1"), os.path.join(tmp, "s1x"))
            with open(os.path.join(tmp, "s1x", "gate.json"), "w") as f:
                json.dump(g, f)
            check("merge " + label, [cavity, "gate", "merge", "s0", "s1x", "--out", "out"], words, tmp, "out")
        ok = subprocess.run([cavity, "gate", "merge", "s0", "s1", "--out", "out"], capture_output=True, text=True, cwd=tmp)
        if ok.returncode != 0:
            failures.append(f"merge of the two shards as judged: exit {ok.returncode}\n{ok.stderr}")

        # A gate output whose images are not what its gate.json judged (a
        # later gate into the folder, killed before its own gate.json; here
        # the older gate.json put back): update refuses, baselines unchanged.
        # Without the CPU's approvals every image is written.
        shutil.copytree(baselines, os.path.join(tmp, "bl"))
        drop_cpu_approvals(os.path.join(tmp, "bl"))
        one = ["gate", "--baselines", "bl", "--matrix", "ci", "--filter", "^corner/alchemy/n16/b4/full/160x90/vk/compute$",
               "--out", "g", "--quiet", "--retries", "0"]
        subprocess.run([cavity, *one], cwd=tmp, check=True, capture_output=True, timeout=300)
        older = open(os.path.join(tmp, "g", "gate.json")).read()
        shader = open(os.path.join(source, "kernels", "ao", "alchemy", "ssao_alchemy.glsl")).read()
        with open(os.path.join(tmp, "edit.glsl"), "w") as f:
            f.write(shader.replace("- P.bias", "- 0.5 * P.bias", 1))
        subprocess.run([cavity, *one, "--kernel-source", "ssao_alchemy.glsl=edit.glsl"], cwd=tmp, capture_output=True,
                       timeout=300)
        with open(os.path.join(tmp, "g", "gate.json"), "w") as f:
            f.write(older)
        images = os.path.join(tmp, "bl", "images", "corner", "alchemy", "n16", "b4", "full", "160x90")
        kept = {n: open(os.path.join(images, n), "rb").read() for n in os.listdir(images)}
        check("update of images gate.json did not judge", [cavity, "baselines", "update", "--from", "g", "--baselines", "bl",
                                                          "--filter", "/vk/compute$"], ["ao.new.f32z", "run the gate again"],
              tmp, "bl/.update-staging")
        if "- P.bias" not in shader or {n: open(os.path.join(images, n), "rb").read() for n in os.listdir(images)} != kept:
            failures.append("update of images gate.json did not judge: the baselines changed (or the edit did not apply)")
    if failures:
        sys.exit("\n".join(failures))
    print(f"{2 * len(BENCH) + len(MANIFEST) + len(merges) + 2} cases")


if __name__ == "__main__":
    main()
