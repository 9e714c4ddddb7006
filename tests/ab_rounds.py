#!/usr/bin/env python3
"""`cavity ab` against builds that misbehave: a stand-in cavity_bench (a
script) that lists its benchmark as the real one does, then, from its third
process on, writes no round file, an empty or malformed one, or dies on a
signal. Each must be exit 4 with one line naming the round file or the
process, and leave an earlier ab's --out as it was; the flags ab sets itself
are refused in --bench-args (exit 2) before anything runs.

    ab_rounds.py CAVITY
"""
import hashlib
import json
import os
import subprocess
import sys
import tempfile

FAKE = r'''#!/usr/bin/env python3
import json, os, signal, sys
mode = os.environ.get("FAKE_MODE", "ok")
args = sys.argv[1:]
out = next((a.split("=", 1)[1] for a in args if a.startswith("--benchmark_out=")), None)
name = "corner/alchemy/n16/b4/full/160x90/gl/compute/iterations:1/manual_time"
if "--other" in args:   # a side that measures another configuration
    name = name.replace("/gl/", "/vk/")
if "--benchmark_list_tests=true" in args:
    print(name)
    sys.exit(0)
counter = os.environ["FAKE_COUNTER"]
n = int(open(counter).read()) if os.path.exists(counter) else 0
open(counter, "w").write(str(n + 1))
def entry(kind):
    return {"name": name, "run_name": name, "run_type": kind, "repetitions": 1, "repetition_index": 0,
            "threads": 1, "iterations": 1, "real_time": 10.0 + n, "cpu_time": 10.0, "time_unit": "ms",
            "pass_ao_ms": 5.0, "label": "clock=wall"}
doc = {"context": {"cavity_software_renderer": "true"}, "benchmarks": [entry("iteration")]}
if n >= 2 and mode != "ok":
    if mode == "signal": os.kill(os.getpid(), signal.SIGSEGV)
    if mode == "nofile": sys.exit(0)
    if mode == "empty": doc["benchmarks"] = []
    if mode == "aggregates": doc["benchmarks"] = [entry("aggregate")]
    if mode == "number": doc["benchmarks"] = 5
    if mode == "entry": doc["benchmarks"] = [1, 2]
    if mode == "runtype": doc["benchmarks"][0]["run_type"] = 7
    if mode == "cut": open(out, "w").write('{"benchmarks": [{"name": "x", "real_ti'); sys.exit(0)
json.dump(doc, open(out, "w"))
'''


def tree(root):
    """A digest of a folder's files, leaving out staging folders (.partial-PID:
    a failed attempt's, with its log, which the next ab removes)."""
    h = hashlib.sha256()
    for dirpath, dirnames, files in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith(".partial-"))
        for f in sorted(files):
            p = os.path.join(dirpath, f)
            h.update(p.encode() + open(p, "rb").read())
    return h.hexdigest()


def main():
    cavity = sys.argv[1]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        bench = os.path.join(tmp, "build", "bench", "cavity_bench")
        os.makedirs(os.path.dirname(bench))
        with open(bench, "w") as f:
            f.write(FAKE)
        os.chmod(bench, 0o755)
        out = os.path.join(tmp, "out")
        counter = os.path.join(tmp, "counter")

        def ab(mode, *extra):
            if os.path.exists(counter):
                os.remove(counter)
            env = dict(os.environ, FAKE_MODE=mode, FAKE_COUNTER=counter)
            return subprocess.run([cavity, "ab", "--a", os.path.join(tmp, "build"), "--b", bench, "--rounds", "3",
                                   "--out", out, *extra], capture_output=True, text=True, env=env, timeout=120)

        first = ab("ok")
        if first.returncode != 0 or not os.path.exists(os.path.join(out, "b_2.json")):
            sys.exit(f"a good ab: exit {first.returncode}\n{first.stderr}")
        # The files compare.json and the table name are where they end up,
        # not in the staging folder ab removed.
        compared = json.load(open(os.path.join(out, "compare.json")))
        for side in ("old", "new"):
            named = compared[side]["file"]
            if not os.path.isfile(named) or ".partial-" in named or ".partial-" in first.stdout:
                failures.append(f"compare.json {side}.file = {named}: not the file in --out")
        before = tree(out)
        cases = {"signal": "killed by signal 11", "nofile": "a_1.json: cannot be read",
                 "empty": "a_1.json: the process measured nothing", "aggregates": "a_1.json: the process measured nothing",
                 "number": "a_1.json: not cavity_bench JSON", "entry": "a_1.json: a benchmark entry is not an object",
                 "runtype": "a_1.json: run_type = 7", "cut": "a_1.json: does not parse"}
        for mode, said in cases.items():
            r = ab(mode)
            errors = [l for l in r.stderr.splitlines() if not l.startswith("cavity ab: round ")]
            if r.returncode != 4 or len(errors) != 1 or said not in errors[0]:
                failures.append(f"{mode}: exit {r.returncode}, expected 4 and one line with '{said}':\n{r.stderr}")
            if tree(out) != before:
                failures.append(f"{mode}: --out changed: {sorted(os.listdir(out))}")
        # Two sides with no configuration in common compared nothing: exit 2.
        r = ab("ok", "--b-args", "--other")
        if r.returncode != 2 or "no configuration and pass in common" not in r.stderr or tree(out) != before:
            failures.append(f"sides with nothing in common: exit {r.returncode}\n{r.stderr}")
        for flag in ("--benchmark_out=x.json", "--benchmark_repetitions=3", "--benchmark_filter=x"):
            r = ab("ok", "--bench-args", "--frames 2 " + flag)
            if r.returncode != 2 or flag.split("=")[0] not in r.stderr or r.stderr.count("\n") != 1:
                failures.append(f"--bench-args {flag}: exit {r.returncode}\n{r.stderr}")
    if failures:
        sys.exit("\n".join(failures))
    print(f"{len(cases) + 4} cases")


if __name__ == "__main__":
    main()
