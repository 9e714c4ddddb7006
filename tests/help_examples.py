#!/usr/bin/env python3
"""Every example of every --help, and every command line of README.md's and
docs/'s code blocks that runs one of the programs, runs as printed: each is
run through the shell in a scratch folder that holds what they name (a copy
of baselines/ with a matrix of the user's, render folders, gate runs,
results and benchmark files, a kernel package, an edited kernel, an OpenEXR
G-buffer, a git commit for $SHA), and each must exit 0. A usage synopsis
(`[--flag VALUE]`, `DIR`) is not a command and is left out; the scripts the
docs name are run by documented_scripts, and the GPU machine's wrappers
(.bundle/) by gpu_scripts.

Three kinds of example are changed before they run, and the change is one
suffix or one substitution, printed beside the example:
  * one that would measure a whole matrix or sweep (cavity run, cavity gate
    and cavity_render that render, cavity quality over every kernel,
    cavity_bench, cavity ab) gets its program's listing flag (--list,
    --benchmark_list_tests): every flag, file and filter is still parsed
    and checked, and the selection printed, but nothing is measured (CI's
    CPU renderer would take minutes; tests elsewhere render them);
  * an image store at https://store.example is a folder store in the
    scratch folder (the HTTP transport is store_http's test);
  * a history database at postgresql://...db.example is an SQLite file
    (the PostgreSQL server is history_postgres's test).
And `cavity history chart` finds a stand-in `chromium` first on PATH that
fails, so it writes its page and no PNG (a headless browser per example
would add seconds each; History.ChartPageIsSelfContained takes the real
screenshot).
A test that cannot find an example in some help fails too: every program
must keep showing how it is used.

    help_examples.py SOURCE_DIR BUILD_DIR
"""
import glob
import gzip
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile

SOURCE, BUILD = (os.path.abspath(p) for p in sys.argv[1:3])
CAVITY = os.path.join(BUILD, "harness", "cavity")
RENDER = os.path.join(BUILD, "render", "cavity_render")
BENCH = os.path.join(BUILD, "bench", "cavity_bench")
PROGRAMS = {"cavity": CAVITY, "cavity_render": RENDER, "cavity_bench": BENCH}
HELPS = [("cavity",), ("cavity", "run"), ("cavity", "quality"), ("cavity", "compare"), ("cavity", "gate"),
         ("cavity", "gate", "judge"), ("cavity", "gate", "merge"), ("cavity", "baselines", "update"),
         ("cavity", "baselines", "approve"), ("cavity", "baselines", "migrate-digests"), ("cavity", "store", "check"),
         ("cavity", "ab"), ("cavity", "history"), ("cavity", "history", "ingest"), ("cavity", "history", "show"),
         ("cavity", "history", "chart"), ("cavity", "history", "alerts"), ("cavity", "kernels", "list"),
         ("cavity", "kernels", "show"), ("cavity", "kernels", "check"), ("cavity", "kernels", "coverage"),
         ("cavity_render",), ("cavity_render", "quality"), ("cavity_bench",)]
# One configuration of each API for the fixtures: cheap on a CPU renderer.
ONE = "^corner/alchemy_fast/n16/b4/full/160x90/{api}/compute$"
SOME = "^(corner|slats)/(alchemy|alchemy_fast)/n16/b4/full/160x90/vk/compute$"
STORED = "^corner/alchemy_fast/n16/b4/full/160x90/"

failures = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        failures.append(what)


def run(args, cwd, **kw):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=600, **kw)


def examples(help_cmd):
    program = PROGRAMS[help_cmd[0]]
    p = subprocess.run([program, *help_cmd[1:], "--help"], capture_output=True, text=True)
    check(p.returncode == 0, f"{' '.join(help_cmd)} --help exits 0")
    text = p.stdout
    at = text.rfind("\nExamples:\n")
    check(at >= 0, f"{' '.join(help_cmd)} --help has examples")
    return [line.strip() for line in text[at:].splitlines()[2:] if line.strip()] if at >= 0 else []


DOC_PROGRAMS = {"build/harness/cavity": "cavity", "build/bench/cavity_bench": "cavity_bench",
                "build/render/cavity_render": "cavity_render", "cavity": "cavity", "cavity_bench": "cavity_bench",
                "cavity_render": "cavity_render"}
SYNOPSIS = re.compile(r"\[--|\[\.\.\.|\.\.\.\]|(?<!\$)\b(DIR|FILE|REGEX|NAME|SHA|DB|URL|RENDER_DIR)\b(?!\.)")


def doc_examples():
    """(where, command) for each command line in README.md's and docs/'s
    indented code blocks that starts with a program: continuation lines
    joined, a trailing comment dropped, the program's path as printed."""
    out = []
    for path in [os.path.join(SOURCE, "README.md")] + sorted(glob.glob(os.path.join(SOURCE, "docs", "*.md"))):
        lines = open(path).read().splitlines()
        i = 0
        while i < len(lines):
            line, where = lines[i], f"{os.path.relpath(path, SOURCE)}:{i + 1}"
            i += 1
            if not line.startswith("    "):
                continue
            cmd = line.strip()
            while cmd.endswith("\\") and i < len(lines):
                cmd = cmd[:-1].rstrip() + " " + lines[i].strip()
                i += 1
            cmd = re.sub(r"\s{2,}#.*$", "", cmd)
            first = cmd.split(" ", 1)[0]
            if first in DOC_PROGRAMS and not SYNOPSIS.search(cmd):
                out.append((where, DOC_PROGRAMS[first] + cmd[len(first):]))
    return out


def write_exr(path, width, height):
    """A G-buffer as cavity run --gbuffer import reads it: an uncompressed
    scanline OpenEXR of float channels N.X, N.Y, N.Z and Z, a plane facing
    the camera 5 units away."""
    names = ["N.X", "N.Y", "N.Z", "Z"]
    value = {"N.X": 0.0, "N.Y": 0.0, "N.Z": 1.0, "Z": 5.0}

    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data
    chlist = b"".join(n.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for n in names) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    row = b"".join(struct.pack("<f", value[n]) * width for n in names)
    block = len(row) + 8
    start = len(header) + 8 * height
    with open(path, "wb") as f:
        f.write(header)
        f.write(b"".join(struct.pack("<Q", start + y * block) for y in range(height)))
        for y in range(height):
            f.write(struct.pack("<ii", y, len(row)) + row)


def fixtures(work):
    """What the examples name, made by the programs themselves."""
    def must(args, what):
        p = run(args, work)
        if p.returncode != 0:
            raise RuntimeError(f"fixture {what}: exit {p.returncode}: {(p.stderr or p.stdout).strip()[-400:]}")
    os.makedirs(os.path.join(work, "baselines"))
    for name in ("matrices.json", "manifest.json", "budgets.json", "approvals.json"):
        shutil.copy(os.path.join(SOURCE, "baselines", name), os.path.join(work, "baselines", name))
    # The store examples check every approval under their key, and a store
    # holds only what some machine rendered into it: here, the CPU
    # renderers' images. So the copy keeps their class's approvals alone.
    approvals = os.path.join(work, "baselines", "approvals.json")
    doc = json.load(open(approvals))
    doc["approvals"] = [a for a in doc["approvals"] if a["device_class"] == "llvmpipe"]
    with open(approvals, "w") as f:
        json.dump(doc, f)
    for name in ("images", "expectations"):
        src = os.path.join(SOURCE, "baselines", name)
        if os.path.isdir(src):
            shutil.copytree(src, os.path.join(work, "baselines", name))
    must([RENDER, "--matrix", "ci", "--filter", "/alchemy_fast/n16/b4/(full|half)/160x90/", "--backend", "vk",
          "--out", "out/render"], "render vk")
    must([RENDER, "--matrix", "ci", "--filter", ONE.format(api="gl"), "--backend", "gl", "--out", "out/render-gl"],
         "render gl")
    shutil.copytree(os.path.join(work, "out/render"), os.path.join(work, "out/render-vk"))
    must([RENDER, "--matrix", "ci", "--filter", "/alchemy_fast/n16/b4/full/160x90/", "--shard", "1/4",
          "--out", "out/render-1"], "render shard 1/4")
    must([CAVITY, "gate", "--matrix", "ci", "--filter", SOME, "--out", "out/gate", "--quiet"], "gate")
    # The image store: every image approved under the key the store examples
    # check, in the checkout's store and in the one standing for a server's.
    must([CAVITY, "gate", "--matrix", "ci", "--filter", STORED, "--out", "out/stored", "--quiet"], "gate stored")
    for store in ("baselines/store", "store/refs"):
        must([CAVITY, "baselines", "approve", "--from", "out/stored", "--store", store, "--why", "fixture"],
             "approve " + store)
    for i in range(2):
        must([CAVITY, "gate", "--matrix", "ci", "--filter", SOME, "--shard", f"{i}/2", "--out", f"out/gate{i}",
              "--quiet"], f"gate shard {i}")
        shutil.copytree(os.path.join(work, f"out/gate{i}"), os.path.join(work, f"out/shard-{i}"))
    must([CAVITY, "run", "--kernel", "alchemy_fast", "--backend", "vk", "--res", "160x90", "--samples", "16",
          "--blur", "4", "--out", "main"], "run")
    shutil.copytree(os.path.join(work, "main"), os.path.join(work, "pr"))
    os.makedirs(os.path.join(work, "out"), exist_ok=True)
    for copy in ("main.json", "pr.json", "old.json", "new.json", "out/results.json"):
        shutil.copy(os.path.join(work, "main", "results.json"), os.path.join(work, copy))
    for side in ("old", "new"):
        shutil.copytree(os.path.join(work, "main"), os.path.join(work, side))
    # Shards of one gate run, and of one render, for the merge and judge examples.
    for i in range(4):
        must([CAVITY, "gate", "--matrix", "ci", "--filter", SOME, "--shard", f"{i}/4", "--out", f"out/s{i}", "--quiet"],
             f"gate shard {i}/4")
    for i in range(2):
        must([RENDER, "--matrix", "ci", "--filter", SOME, "--shard", f"{i}/2", "--out", f"out/r{i}"], f"render {i}/2")
    write_exr(os.path.join(work, "capture.exr"), 1920, 1080)
    # A benchmark of the H200 (1920x1080): what the examples that name a GPU
    # (--device H200) and a cost file read.
    # Its alchemy configurations only: a history chart draws every one, in
    # a page Chromium then opens.
    with gzip.open(os.path.join(SOURCE, "tests", "data", "2026-11-30_h200_full_sweep.json.gz"), "rt") as f:
        sweep = json.load(f)
    sweep["benchmarks"] = [b for b in sweep["benchmarks"] if re.match(r"corner/alchemy(_fast)?/n16/b4/", b["name"])]
    json.dump(sweep, open(os.path.join(work, "bench.json"), "w"))
    shutil.copy(os.path.join(SOURCE, "kernels", "ao", "alchemy_fast", "ssao_alchemy_fast.glsl"),
                os.path.join(work, "edit.glsl"))
    for name in ("my_alchemy.glsl", "my_edit.glsl"):
        shutil.copy(os.path.join(SOURCE, "kernels", "ao", "alchemy", "ssao_alchemy.glsl"), os.path.join(work, name))
    pkg = os.path.join(work, "my_kernels", "my_ao")
    os.makedirs(pkg)
    toml = open(os.path.join(SOURCE, "kernels", "ao", "alchemy", "kernel.toml")).read()
    toml = toml.replace('name = "alchemy"', 'name = "my_ao"').replace('file = "ssao_alchemy.glsl"', 'file = "my_ao.glsl"')
    open(os.path.join(pkg, "kernel.toml"), "w").write(toml)
    shutil.copy(os.path.join(work, "my_alchemy.glsl"), os.path.join(pkg, "my_ao.glsl"))
    os.makedirs(os.path.join(work, "references"))
    os.symlink(BUILD, os.path.join(work, "build"))   # the checkout's build folder
    os.symlink(os.path.join(BUILD, "bench"), os.path.join(work, ".bundle"))
    for side in ("main", "pr"):
        os.symlink(BUILD, os.path.join(work, side, "build"))
        os.symlink(os.path.join(BUILD, "bench"), os.path.join(work, side, ".bundle"))
    # A commit for $(git rev-parse HEAD) and $SHA.
    env = dict(os.environ, GIT_AUTHOR_NAME="t", GIT_AUTHOR_EMAIL="t@example.com", GIT_COMMITTER_NAME="t",
               GIT_COMMITTER_EMAIL="t@example.com")
    for args in (["git", "init", "-q"], ["git", "add", "main.json"], ["git", "commit", "-q", "-m", "fixture"]):
        p = run(args, work, env=env)
        if p.returncode != 0:
            raise RuntimeError(f"fixture git: {p.stderr}")
    return run(["git", "rev-parse", "HEAD"], work).stdout.strip()


# The programs (or subcommands) whose examples measure: their listing flag.
LISTING = [(r"^cavity run ", "--list"), (r"^cavity gate(?! (judge|merge))( |$)", "--list"),
           (r"^cavity quality ", "--list"), (r"^cavity_render (?!quality)", "--list"),
           (r"^cavity_render quality ", "--list"), (r"^cavity ab ", "--list"),
           (r"^cavity_bench ", "--benchmark_list_tests")]


def baselines_as_checked_out(work, example):
    """baselines/'s files as the fixtures left them, before each example, so
    that one example's approvals (a digest marked known bad) or updates do not
    decide the next one's verdict; with "--matrix mine", the user's own
    matrix added (the README's "a matrix of yours in matrices.json")."""
    for name, text in PRISTINE.items():
        open(os.path.join(work, "baselines", name), "w").write(text)
    if "--matrix mine" in example:
        path = os.path.join(work, "baselines", "matrices.json")
        matrices = json.load(open(path))
        matrices["mine"] = {"description": "my_ao, one configuration per API", "frames": 2, "warmup": 0,
                            "groups": [{"scenes": ["corner"], "kernels": ["my_ao"], "samples": [16], "blurs": [4],
                                        "resolutions": ["full"], "sizes": ["160x90"], "apis": ["gl", "vk"],
                                        "stages": ["compute"]}]}
        json.dump(matrices, open(path, "w"), indent=1)


PRISTINE = {}


def adapt(example, work):
    """The example as it runs here, and what was changed (or "")."""
    cmd, changes = example, []
    if "https://store.example/refs" in cmd:
        cmd = cmd.replace("https://store.example/refs", os.path.join(work, "store", "refs"))
        changes.append("the store a folder")
    if "postgresql://" in cmd:
        cmd = re.sub(r'"postgresql://[^"]*"|postgresql://\S+', "history.sqlite", cmd)
        changes.append("the database an SQLite file")
    for pattern, flag in LISTING:
        if re.search(pattern, cmd) and flag not in cmd.split():
            cmd += " " + flag
            changes.append(flag)
            break
    # The programs by their build paths, the example's words otherwise as printed.
    first, _, rest = cmd.partition(" ")
    cmd = PROGRAMS[first] + (" " + rest if rest else "")
    return cmd, ", ".join(changes)


def main():
    work = tempfile.mkdtemp(prefix="help-examples-")
    try:
        sha = fixtures(work)
        for name in ("matrices.json", "manifest.json", "budgets.json", "approvals.json"):
            PRISTINE[name] = open(os.path.join(work, "baselines", name)).read()
        shim = os.path.join(work, "no-browser")
        os.makedirs(shim)
        with open(os.path.join(shim, "chromium"), "w") as f:
            f.write("#!/bin/sh\nexit 3\n")
        os.chmod(os.path.join(shim, "chromium"), 0o755)
        env = dict(os.environ, SHA=sha, CI_JOB_URL="https://ci.example/jobs/1",
                   PATH=shim + os.pathsep + os.environ.get("PATH", ""))
        # Ingest first: the history examples that read a database need one.
        todo = [(" ".join(h) + " --help", e) for h in HELPS for e in examples(h)]
        docs = doc_examples()
        check(len(docs) >= 40, f"README.md and docs/ hold {len(docs)} command lines (at least 40)")
        todo += docs
        todo.sort(key=lambda he: 0 if " ingest " in he[1] else 1)
        print(f"{len(todo)} examples")
        for where, example in todo:
            if example.split()[0] not in PROGRAMS:
                check(False, f"{example}: starts with a program")
                continue
            cmd, changed = adapt(example, work)
            baselines_as_checked_out(work, example)
            p = subprocess.run(cmd, shell=True, cwd=work, env=env, capture_output=True, text=True, timeout=600)
            last = (p.stderr.strip() or p.stdout.strip()).splitlines()[-1:] if p.returncode else []
            check(p.returncode == 0, f"{where}: {example}" + (f"   [{changed}]" if changed else "") +
                  (f": exit {p.returncode}: {last}" if last else ""))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if failures:
        print(f"{len(failures)} failed")
        sys.exit(1)


main()
