#!/usr/bin/env python3
"""`cavity run` killed with SIGKILL while it renders leaves --out as it was
(all or nothing): its images are written under a staging folder in --out
and move in only when every configuration has run. The kill comes once the
staging folder holds an image (an event, not a time), and a later run
removes the killed run's staging folder and moves its own images in. A run
in which nothing ran leaves a results.json of its errors and none of the
earlier run's table or page.

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
        print("killed run: --out unchanged, and the next run cleaned up" if not failures else f"{failures} failures")
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
