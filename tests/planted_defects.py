#!/usr/bin/env python3
"""scripts/planted_defects.sh's defects still apply, and each still fails
the CPU gate: the script writes every defect (it fails when an edit no
longer applies to its kernel file), and `cavity gate` with that edit in
place of the file (--kernel-source), on the configurations it touches,
exits 1 with a failed image. A defect that an edit to the kernels has made
harmless, or that no longer reaches the configurations it names, fails here
instead of silently passing the GPU store run that reads the same list.

    planted_defects.py SOURCE_DIR BUILD_DIR

Each defect is judged on the Vulkan compute configurations it touches
(both APIs compile the same GLSL; the gate's own tests hold GL to Vulkan).
"""
import json
import os
import re
import subprocess
import sys
import tempfile


MAX_CONFIGS = 6


def main():
    source, build = (os.path.abspath(p) for p in sys.argv[1:3])
    cavity = os.path.join(build, "harness", "cavity")
    with tempfile.TemporaryDirectory() as tmp:
        defects = os.path.join(tmp, "defects")
        r = subprocess.run([os.path.join(source, "scripts", "planted_defects.sh"), defects],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = [line.split() for line in open(os.path.join(defects, "list.txt")) if line.strip()]
        assert len(rows) >= 8, rows
        failures = []
        for name, file, touches in rows:
            out = os.path.join(tmp, "gate_" + name)
            ids = subprocess.run([cavity, "gate", "--matrix", "ci", "--filter", f"^(?=.*/vk/compute$).*{touches}",
                                  "--list"], capture_output=True, text=True).stdout.split()
            if not ids:
                failures.append(f"{name} ({file}): touches no configuration of the ci matrix ({touches})")
                continue
            # A defect in a shared pass (the composite) touches most of the
            # matrix: every few of its configurations show it as well as all.
            ids = ids[::-(-len(ids) // MAX_CONFIGS)]
            # --retries 0: a failing configuration is rendered once; the
            # gate's retries tell a flaky image from a steady one, which a
            # planted defect is by construction.
            cmd = [cavity, "gate", "--matrix", "ci", "--retries", "0",
                   "--filter", "^(" + "|".join(re.escape(i) for i in ids) + ")$",
                   "--kernel-source", f"{file}={os.path.join(defects, name + '.glsl')}",
                   "--out", out, "--quiet"]
            g = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
            if g.returncode != 1:
                failures.append(f"{name} ({file}): the gate exited {g.returncode}, not 1: "
                                f"{(g.stderr or g.stdout).strip().splitlines()[-1:] }")
                continue
            gate = json.load(open(os.path.join(out, "gate.json")))
            text = json.dumps(gate)
            if '"fail"' not in text:
                failures.append(f"{name}: exit 1 but no configuration failed in gate.json")
            else:
                print(f"{name}: fails the gate ({file}, {touches})")
        for f in failures:
            print(f"FAIL {f}")
        print(f"planted defects: {len(rows)} written; {len(rows) - len(failures)} fail the gate; "
              f"{len(failures)} do not")
        sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
