#!/usr/bin/env python3
"""One step of scripts/bisect.sh, run by `git bisect run` in the worktree at
the commit to test: build it in its own folder, run the configuration, and
answer with the gate's verdict (image mode) or `cavity compare`'s (pass
mode). Exit 0 good, 1 bad, 125 skip (does not build, or no verdict). The
settings come from bisect.sh through CAVITY_BISECT_* variables; with
CAVITY_BISECT_REFERENCE=1 it builds and runs GOOD as the pass mode's
reference instead."""
import json
import os
import re
import shutil
import subprocess
import sys

GOOD, BAD, SKIP = 0, 1, 125

DEFAULT_BUILD = ('cmake -S "$SRC" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null && '
                 'cmake --build "$BUILD" -j "$(nproc)" >/dev/null')
DEFAULT_GATE = ('"$BUILD/harness/cavity" gate --matrix "$MATRIX" --baselines "$BASELINES" '
                '--filter "$ID_REGEX" --retries 0 --out "$OUT" >/dev/null')
DEFAULT_RUN = '"$BUILD/harness/cavity" run $RUN_FLAGS --frames "$FRAMES" --out "$OUT" >/dev/null'

ID_RE = re.compile(r"^(?P<scene>[a-z_]+)(\+(?P<gbuffer>[a-z]+))?/(?P<kernel>[a-z_]+)/n(?P<n>\d+)/b(?P<b>\d+)/"
                   r"(?P<res>full|half)/(?P<size>\d+x\d+)/(?P<api>gl|vk)/(?P<stage>compute|fragment)$")


def run_flags(config_id):
    """`cavity run` flags for a configuration id (README, Configuration ids)."""
    m = ID_RE.match(config_id)
    if not m:
        return None
    flags = ["--scene", m["scene"], "--kernel", m["kernel"], "--samples", m["n"], "--blur", m["b"],
             "--resolution", m["res"], "--res", m["size"], "--backend", m["api"], "--stage", m["stage"]]
    if m["gbuffer"]:
        flags += ["--gbuffer", m["gbuffer"]]
    return " ".join(flags)


def shell(command, env):
    return subprocess.run(["bash", "-c", command], env=env).returncode


def gate_verdict(gate_json, config_id, image):
    """(bad, numbers) from a cavity.gate/1 file, or None when it has no verdict for the id."""
    try:
        with open(gate_json) as f:
            g = json.load(f)
    except (OSError, ValueError):
        return None
    rows = [r for r in g.get("results", []) if r.get("id") == config_id and r.get("repetition", 0) == 0]
    if not rows or rows[0].get("error"):
        return None
    r = rows[0]
    images = [i for i in r["images"] if not image or i["image"] == image]
    if image and not images:
        return None
    parts = []
    for i in images:
        m = i.get("metrics") or {}
        parts.append(f'{i["image"]}: max abs {m.get("max_abs", "-")}, RMSE {m.get("rmse", "-")}, '
                     f'SSIM {m.get("ssim", "-")}' + ("" if i["passed"] else " FAIL"))
    bad = any(not i["passed"] for i in images) if image else not r["passed"]
    return bad, "; ".join(parts)


def compare_verdict(compare, reference, results, work, config_id, pass_name):
    out = os.path.join(work, "compare.json")
    p = subprocess.run([compare, "compare", reference, results, "--json", out], capture_output=True, text=True)
    if p.returncode != 0:
        return None
    with open(out) as f:
        rows = [r for r in json.load(f)["rows"] if r["id"] == config_id and r["pass"] == pass_name]
    if not rows or rows[0]["verdict"] not in ("slower", "faster", "same"):
        return None
    r = rows[0]
    change = "-" if r["change_pct"] is None else f'{r["change_pct"]:+.2f}%'
    return r["verdict"] == "slower", (f'{pass_name}: {r["old_median_ms"]:.4g} -> {r["new_median_ms"]:.4g} ms, '
                                      f'change {change}, p {r["p"]:.3g}, {r["verdict"]}')


def main():
    e = os.environ
    work, config_id = e["CAVITY_BISECT_WORK"], e["CAVITY_BISECT_ID"]
    image, pass_name = e.get("CAVITY_BISECT_IMAGE", ""), e.get("CAVITY_BISECT_PASS", "")
    reference_mode = e.get("CAVITY_BISECT_REFERENCE") == "1"
    sha = subprocess.run(["git", "rev-parse", "HEAD"], capture_output=True, text=True, check=True).stdout.strip()
    subject = subprocess.run(["git", "log", "-1", "--format=%s"], capture_output=True, text=True).stdout.strip()
    build = os.path.join(work, "build", sha)
    out = os.path.join(work, "reference" if reference_mode else "run", sha)
    os.makedirs(out, exist_ok=True)
    env = dict(e, SRC=os.getcwd(), BUILD=build, OUT=out, ID=config_id, ID_REGEX="^" + re.escape(config_id) + "$",
               MATRIX=e.get("CAVITY_BISECT_MATRIX", "ci"), BASELINES=e.get("CAVITY_BISECT_BASELINES", ""),
               FRAMES=e.get("CAVITY_BISECT_FRAMES", "30"), RUN_FLAGS=run_flags(config_id) or "")

    def answer(code, text):
        word = {GOOD: "good", BAD: "bad", SKIP: "skip"}[code]
        line = f"{sha[:12]} {word:4}  {text}  ({subject})"
        if not reference_mode:
            with open(os.path.join(work, "numbers", sha + ".txt"), "w") as f:
                f.write(line + "\n")
            with open(os.path.join(work, "tested.txt"), "a") as f:
                f.write(line + "\n")
        print(line)
        return code

    if pass_name and not env["RUN_FLAGS"] and "CAVITY_BISECT_RUN" not in e:
        print(f"bisect_step.py: --id {config_id}: not a configuration id", file=sys.stderr)
        return SKIP
    if shell(e.get("CAVITY_BISECT_BUILD", DEFAULT_BUILD), env) != 0:
        return answer(SKIP, "does not build")
    run = e.get("CAVITY_BISECT_RUN", DEFAULT_RUN if pass_name else DEFAULT_GATE)
    rc = shell(run, env)
    if pass_name:
        results = os.path.join(out, "results.json")
        if rc != 0 or not os.path.exists(results):
            return answer(SKIP, f"run exited {rc} without results.json")
        if reference_mode:
            shutil.copy(results, os.path.join(work, "reference.json"))
            return GOOD
        reference = os.path.join(work, "reference.json")
        v = compare_verdict(e["CAVITY_BISECT_COMPARE"], reference, results, out, config_id, pass_name)
    else:
        if rc not in (0, 1):
            return answer(SKIP, f"gate exited {rc} (no verdict)")
        v = gate_verdict(os.path.join(out, "gate.json"), config_id, image)
    if v is None:
        return answer(SKIP, "no verdict for " + config_id)
    bad, numbers = v
    return answer(BAD if bad else GOOD, numbers)


if __name__ == "__main__":
    sys.exit(main())
