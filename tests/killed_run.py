#!/usr/bin/env python3
"""`cavity run` and `cavity gate` killed with SIGKILL while they render
leave --out as it was (all or nothing): their images are written under a
staging folder in --out and move in only when every configuration has run.
The kill comes once the staging folder holds an image (an event, not a
time), and a later run removes the killed run's staging folder and moves
its own images in. A run in which nothing ran leaves a results.json of its
errors and none of the earlier run's table or page. A gate's reports name
only images that are there.

    killed_run.py CAVITY
"""
import hashlib
import json
import os
import signal
import subprocess
import sys
import tempfile
import time


def contents(root):
    """Every file under root but the staging folders, with its digest."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if not d.startswith(".partial-")]
        for name in filenames:
            p = os.path.join(dirpath, name)
            with open(p, "rb") as f:
                out[os.path.relpath(p, root)] = hashlib.sha256(f.read()).hexdigest()
    return out


def main():
    cavity = sys.argv[1]
    base = ["run", "--backend", "vk", "--kernel", "alchemy", "--res", "64x36", "--warmup", "0", "--quiet"]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        subprocess.run([cavity] + base + ["--frames", "2", "--out", out], check=True, capture_output=True)
        before = contents(out)
        # A long run of other configurations into the same folder.
        p = subprocess.Popen([cavity] + base + ["--samples", "4,8,32,64", "--blur", "0,2", "--frames", "2000",
                                                "--max-noise", "0", "--out", out],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        staging = os.path.join(out, f".partial-{p.pid}")
        deadline = time.time() + 300
        while time.time() < deadline and p.poll() is None:
            if any(f.endswith(".exr") for _, _, files in os.walk(staging) for f in files):
                break
            time.sleep(0.05)
        if p.poll() is not None:
            print(f"FAIL the run ended (exit {p.returncode}) before it had written an image to kill it at")
            return 1
        p.send_signal(signal.SIGKILL)
        p.wait()
        failures = 0
        after = contents(out)
        if after != before:
            changed = sorted(set(after) ^ set(before) | {k for k in after if before.get(k) != after[k]})
            print(f"FAIL a killed run changed --out: {changed[:5]}")
            failures += 1
        if not os.path.isdir(staging):
            print("FAIL the killed run wrote no staging folder (the kill came before any image?)")
            failures += 1
        r = subprocess.run([cavity] + base + ["--samples", "8", "--frames", "2", "--out", out], capture_output=True,
                           text=True)
        if r.returncode != 0 or os.path.exists(staging):
            print(f"FAIL the next run: exit {r.returncode}, killed run's staging folder left: {os.path.exists(staging)}")
            failures += 1
        if not os.path.isfile(os.path.join(out, "corner/alchemy/n8/b4/full/64x36/vk/compute/ao.exr")):
            print("FAIL the next run's images did not move into --out")
            failures += 1
        leftovers = [d for d in os.listdir(out) if d.startswith(".partial-")]
        if leftovers:
            print(f"FAIL staging folders left after a whole run: {leftovers}")
            failures += 1
        # A run in which no configuration ran (no such device) records its
        # error, and leaves no earlier run's table or page to be read as its own.
        r = subprocess.run([cavity] + base + ["--frames", "2", "--device", "5", "--out", out], capture_output=True,
                           text=True)
        with open(os.path.join(out, "results.json")) as f:
            doc = json.load(f)
        stale = [n for n in ("table.txt", "index.html") if os.path.exists(os.path.join(out, n))]
        if r.returncode != 3 or doc["runs"] or not doc["errors"] or "--device 5" not in doc["errors"][0]["message"] \
                or stale:
            print(f"FAIL a run where nothing ran: exit {r.returncode}, runs {len(doc['runs'])}, "
                  f"errors {doc['errors']}, earlier files left {stale}")
            failures += 1
        failures += killed_gate(cavity, tmp)
        print("killed run and gate: --out unchanged, and the next one cleaned up" if not failures
              else f"{failures} failures")
        return 1 if failures else 0


def killed_when_staged(cmd, cwd, out):
    """Starts cmd in cwd, kills it once its staging folder in out holds a
    file; whether it got that far."""
    p = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    staging = os.path.join(out, f".partial-{p.pid}")
    deadline = time.time() + 300
    while time.time() < deadline and p.poll() is None:
        if any(files for _, _, files in os.walk(staging)):
            break
        time.sleep(0.05)
    if p.poll() is not None:
        print(f"FAIL {cmd[1]} ended (exit {p.returncode}) before it had written an image to kill it at")
        return False
    p.send_signal(signal.SIGKILL)
    p.wait()
    return True


def named_images(out):
    """The images the gate.json in out names, and those of them missing."""
    with open(os.path.join(out, "gate.json")) as f:
        doc = json.load(f)
    named = [v for r in doc["results"] for i in r["images"] for k, v in i.items()
             if k in ("new_exact", "new_png", "diff_png") and v]
    return named, [n for n in named if not os.path.isfile(os.path.join(os.path.dirname(out), n))]


def killed_gate(cavity, tmp):
    """A failing gate's output, a longer gate killed into the same folder,
    then a passing gate: each leaves one whole output."""
    failures = 0
    out = os.path.join(tmp, "gate")
    one = "^corner/alchemy_fast/n16/b4/full/160x90/vk/compute$"
    gate = [cavity, "gate", "--matrix", "ci", "--quiet", "--retries", "0", "--out", "gate"]
    env = dict(os.environ, CAVITY_TEST_FLAKY="alchemy_fast")   # the test hook: its first render fails
    r = subprocess.run(gate + ["--filter", one], cwd=tmp, env=env, capture_output=True, text=True)
    named, missing = named_images(out)
    if r.returncode != 1 or not named or missing:
        print(f"FAIL the failing gate: exit {r.returncode}, {len(named)} images named, missing {missing[:3]}")
        return 1
    before = contents(out)
    if not killed_when_staged(gate + ["--filter", "^(corner|slats)/"], tmp, out):
        return 1
    after = contents(out)
    if after != before:
        changed = sorted(set(after) ^ set(before) | {k for k in after if before.get(k) != after[k]})
        print(f"FAIL a killed gate changed --out: {changed[:5]}")
        failures += 1
    r = subprocess.run(gate + ["--filter", one], cwd=tmp, capture_output=True, text=True)
    named, missing = named_images(out)
    leftovers = [d for d in os.listdir(out) if d.startswith(".partial-")]
    stray = sorted(set(contents(out)) - {os.path.relpath(n, "gate") for n in named}
                   - {"gate.json", "index.html", "junit.xml", "status.json", "summary.md"})
    if r.returncode != 0 or missing or leftovers or any(not s.endswith(".f32z") and ".new." not in s for s in stray):
        print(f"FAIL the next gate: exit {r.returncode}, missing {missing[:3]}, staging left {leftovers}, "
              f"files of no report {stray[:3]}")
        failures += 1
    return failures


if __name__ == "__main__":
    sys.exit(main())
