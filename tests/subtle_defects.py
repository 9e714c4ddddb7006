#!/usr/bin/env python3
"""The four subtle defects (scripts/planted_defects.sh --subtle) fail the
CPU gate clearly, not by a hair: each is gated with its edit in place of
the kernel file (--kernel-source) on every Vulkan compute configuration of
the ci matrix that it touches, the gate exits 1, and the weakest failing
configuration is still well over its tolerance. A configuration's severity
is the report's: the largest ratio of a metric to its tolerance over its
images (harness/report/verdict_text.cpp).

    subtle_defects.py SOURCE_DIR BUILD_DIR

The floor, 3x, is what the CPU renderers' own tolerances (manifest.json,
the llvmpipe entry) reach on this matrix (docs/gate.md, "Subtle errors",
study `2026-12-06_cpu_subtle_defects`); under the cross-device tolerances
alone three of the four fail under it.
"""
import json
import math
import os
import subprocess
import sys
import tempfile

FLOOR = 3.0


def over(v, limit):
    return v / limit if limit > 0 else (math.inf if v > 0 else 0.0)


def severity(result):
    worst = 0.0
    for i in result["images"]:
        m, t = i.get("metrics"), i["tolerance"]
        if not m:
            continue
        worst = max(worst, over(m["max_abs"], t["max_abs"]), over(m["mean_abs"], t["mean_abs"]),
                    over(m["rmse"], t["rmse"]), over(m["over_threshold_share"], t["over_threshold_share"]),
                    over(1 - m["ssim"], 1 - t["ssim_min"]),
                    t["psnr_min"] / m["psnr"] if isinstance(m["psnr"], (int, float)) and 0 < m["psnr"] < 1e299 else 0)
        if m["flip_mean"] >= 0:
            worst = max(worst, over(m["flip_mean"], t["flip_mean_max"]),
                        over(m["differing_share"], t["differing_share_max"]))
    return worst


def main():
    source, build = (os.path.abspath(p) for p in sys.argv[1:3])
    cavity = os.path.join(build, "harness", "cavity")
    env = dict(os.environ, CAVITY_STORE=os.path.join(tempfile.gettempdir(), "no-store-here"))
    with tempfile.TemporaryDirectory() as tmp:
        defects = os.path.join(tmp, "defects")
        r = subprocess.run([os.path.join(source, "scripts", "planted_defects.sh"), defects, "--subtle"],
                           capture_output=True, text=True)
        assert r.returncode == 0, r.stderr
        rows = [line.split() for line in open(os.path.join(defects, "list.txt")) if line.strip()]
        assert len(rows) == 4, rows
        failures = []
        for name, file, touches in rows:
            out = os.path.join(tmp, "gate_" + name)
            # --retries 0: a planted defect is steady by construction. No
            # image store (a clone has none): changed images are judged
            # against the stored baselines, as in CI.
            cmd = [cavity, "gate", "--matrix", "ci", "--retries", "0", "--quiet",
                   "--filter", f"^(?=.*/vk/compute$).*{touches}",
                   "--kernel-source", f"{file}={os.path.join(defects, name + '.glsl')}", "--out", out]
            g = subprocess.run(cmd, capture_output=True, text=True, timeout=1200, env=env, cwd=source)
            if g.returncode != 1:
                failures.append(f"{name}: the gate exited {g.returncode}, not 1: "
                                f"{(g.stderr or g.stdout).strip().splitlines()[-1:]}")
                continue
            results = json.load(open(os.path.join(out, "gate.json")))["results"]
            failed = sorted((severity(x), x["id"]) for x in results if x["verdict"] == "fail")
            if not failed:
                failures.append(f"{name}: exit 1 but no configuration failed in gate.json")
                continue
            weakest, wid = failed[0]
            line = (f"{name}: {len(failed)} of {len(results)} configurations fail, the weakest at "
                    f"{weakest:.2f}x ({wid}), floor {FLOOR}x")
            print(line)
            if weakest < FLOOR:
                failures.append(line)
        for f in failures:
            print(f"FAIL {f}")
        sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
