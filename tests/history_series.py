#!/usr/bin/env python3
"""Writes a history of cavity_bench JSON files, one per commit, made from a
real recorded sweep (the H200's of 2026-11-30, a copy in tests/data/): its
context, names, labels and counters kept, the times of a few configurations
scaled per commit with seeded noise and planted steps, the repetitions Google
Benchmark would write.

    history_series.py SOURCE_DIR OUT_DIR [--commits N]

Prints one line per file: COMMIT DATE PATH. The planted steps (the tests
check that alerts finds them, at the right commit, and nothing else):
  corner/alchemy/n16/b4/full/1920x1080/gl/compute  pass ao    a tenth slower from commit 12
  corner/alchemy/n16/b4/full/1920x1080/vk/compute  pass blur  six hundredths faster from commit 7
"""
import copy
import gzip
import hashlib
import json
import os
import random
import sys

SOURCE, OUT = sys.argv[1], sys.argv[2]
N = int(sys.argv[sys.argv.index("--commits") + 1]) if "--commits" in sys.argv else 20
KEEP = ["corner/alchemy/n16/b4/full/1920x1080/gl/compute", "corner/alchemy/n16/b4/full/1920x1080/vk/compute",
        "corner/alchemy/n4/b4/full/1920x1080/gl/compute"]
STEPS = {("corner/alchemy/n16/b4/full/1920x1080/gl/compute", "ao"): (12, 1.10),
         ("corner/alchemy/n16/b4/full/1920x1080/vk/compute", "blur"): (7, 0.94)}
REPS = 5


def commit_sha(i):
    return hashlib.sha1(b"cavity history commit %d" % i).hexdigest()


def main():
    with gzip.open(os.path.join(SOURCE, "tests/data/2026-11-30_h200_full_sweep.json.gz"), "rt") as f:
        doc = json.load(f)
    base = {b["run_name"].split("/iterations")[0]: b for b in doc["benchmarks"]
            if b["run_name"].split("/iterations")[0] in KEEP}
    os.makedirs(OUT, exist_ok=True)
    rng = random.Random(20261203)
    for i in range(N):
        out = {"context": copy.deepcopy(doc["context"]), "benchmarks": []}
        date = "2026-11-%02dT%02d:00:00+00:00" % (1 + i // 2, 8 + 6 * (i % 2))
        out["context"]["date"] = date
        for cid in KEEP:
            for r in range(REPS):
                b = copy.deepcopy(base[cid])
                b["repetitions"], b["repetition_index"] = REPS, r
                total = 0.0
                for key in [k for k in b if k.startswith("pass_") and k.endswith("_ms")]:
                    pas = key[5:-3]
                    at, factor = STEPS.get((cid, pas), (N + 1, 1.0))
                    v = b[key] * (factor if i >= at else 1.0) * (1 + rng.gauss(0, 0.01))
                    b[key] = v
                    total += v
                b["real_time"] = total
                b["sm_mhz_median"], b["mem_mhz_median"] = 1980.0, 3201.0
                out["benchmarks"].append(b)
        path = os.path.join(OUT, "bench_%02d.json" % i)
        with open(path, "w") as f:
            json.dump(out, f)
        print(commit_sha(i), date, path)


if __name__ == "__main__":
    main()
