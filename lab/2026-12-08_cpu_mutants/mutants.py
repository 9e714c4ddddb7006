#!/usr/bin/env python3
"""Random one-token mutants of the built-in kernels' GLSL, each gated on the
CPU renderers as a pull request with that edit would be (--kernel-source),
to find code whose defects no stored matrix sees.

    mutants.py SOURCE_DIR BUILD_DIR OUT_DIR [--count N] [--seed S] [--matrix M] [--filter REGEX]

For each mutant: one code line of one kernel file (comments, preprocessor
lines and declarations left alone) gets one of the operators below, the gate
runs on MATRIX (default ci) restricted to FILTER (default Vulkan compute),
and OUT_DIR/results.jsonl gets a line: the file, line, operator, the edit,
the gate's exit (1 killed, 0 survived, 2 refused: no configuration compiles
the file, or it does not compile), the failing configurations and seconds.
"""
import argparse
import json
import os
import random
import re
import subprocess
import time

OPERATORS = [
    ("plus_minus", r" \+ ", " - "),
    ("minus_plus", r" - ", " + "),
    ("times_div", r" \* ", " / "),
    ("lt_le", r" < ", " <= "),
    ("le_lt", r" <= ", " < "),
    ("gt_ge", r" > ", " >= "),
    ("ge_gt", r" >= ", " > "),
    ("max_min", r"\bmax\(", "min("),
    ("min_max", r"\bmin\(", "max("),
    ("swizzle_xy", r"\.x\b", ".y"),
    ("swizzle_yx", r"\.y\b", ".x"),
    ("float_up", r"(?<![\w.])(\d+\.\d+)(?![\w.])", None),   # a float literal 10% larger
    ("int_up", r"(?<![\w.])([1-9]\d*)(?![\w.])", None),      # an int literal plus one
]

SKIP = re.compile(r"^\s*(//|#|\*|/\*|layout|uniform|buffer|struct|in |out |shared |precision)")


def mutate(line, op, rng):
    name, pattern, repl = op
    hits = list(re.finditer(pattern, line))
    if not hits:
        return None
    m = rng.choice(hits)
    if name == "float_up":
        new = repr(round(float(m.group(1)) * 1.1, 6))
    elif name == "int_up":
        new = str(int(m.group(1)) + 1)
    else:
        new = repl
    return line[:m.start()] + new + line[m.end():]


def code_lines(text):
    lines = text.split("\n")
    depth, out = 0, []
    for i, line in enumerate(lines):
        code = line.split("//")[0]
        if depth > 0 and code.strip() and not SKIP.match(line):
            out.append(i)
        depth += code.count("{") - code.count("}")
    return lines, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("source")
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--matrix", default="ci")
    ap.add_argument("--filter", default="/vk/compute$")
    ap.add_argument("--files", default="", help="regex of kernel files (relative to kernels/)")
    ap.add_argument("--dry", action="store_true", help="print the edits, gate nothing")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    kernels = os.path.join(a.source, "kernels")
    files = sorted(os.path.relpath(os.path.join(d, f), kernels) for d, _, fs in os.walk(kernels) for f in fs
                   if f.endswith(".glsl") and "package" not in d)
    files = [f for f in files if re.search(a.files, f)]
    os.makedirs(a.out, exist_ok=True)
    cavity = os.path.join(a.build, "harness", "cavity")
    env = dict(os.environ, CAVITY_STORE=os.path.join(a.out, "no-store-here"))
    done = 0
    with open(os.path.join(a.out, "results.jsonl"), "a") as log:
        while done < a.count:
            f = rng.choice(files)
            text = open(os.path.join(kernels, f)).read()
            lines, candidates = code_lines(text)
            if not candidates:
                continue
            i = rng.choice(candidates)
            op = rng.choice(OPERATORS)
            new = mutate(lines[i], op, rng)
            if new is None or new == lines[i]:
                continue
            if a.dry:
                print(f"{f}:{i + 1} {op[0]}: {lines[i].strip()}  ->  {new.strip()}")
                done += 1
                continue
            mutant = os.path.join(a.out, f"m{a.seed}_{done:03d}.glsl")
            with open(mutant, "w") as m:
                m.write("\n".join(lines[:i] + [new] + lines[i + 1:]))
            gate_out = os.path.join(a.out, "gate")
            t = time.time()
            g = subprocess.run([cavity, "gate", "--matrix", a.matrix, "--retries", "0", "--quiet", "--filter", a.filter,
                                "--kernel-source", f"{f}={mutant}", "--out", gate_out],
                               capture_output=True, text=True, env=env, cwd=a.source)
            failed = []
            if g.returncode == 1 and os.path.exists(os.path.join(gate_out, "gate.json")):
                doc = json.load(open(os.path.join(gate_out, "gate.json")))
                failed = [r["id"] for r in doc["results"] if r["verdict"] == "fail"]
            row = {"mutant": os.path.basename(mutant), "file": f, "line": i + 1, "op": op[0],
                   "before": lines[i].strip(), "after": new.strip(), "exit": g.returncode,
                   "failed": len(failed), "first_failed": failed[:3], "seconds": round(time.time() - t, 1),
                   "why": (g.stderr.strip().splitlines() or [""])[-1][:300] if g.returncode == 2 else ""}
            log.write(json.dumps(row) + "\n")
            log.flush()
            print(f"{row['mutant']} {f}:{i + 1} {op[0]} exit {g.returncode} failed {len(failed)} "
                  f"({row['seconds']} s) {row['why'][:120]}", flush=True)
            done += 1


if __name__ == "__main__":
    main()
