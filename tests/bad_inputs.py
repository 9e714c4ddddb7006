#!/usr/bin/env python3
"""Every bad input against the real binaries: each must exit with its
documented code (README "Exit codes"), print exactly one line on stderr that
names the flag or file and the value, write nothing, and never crash.

    bad_inputs.py CAVITY CAVITY_BENCH SOURCE_DIR [NAME_REGEX]

Each case runs in a fresh temporary folder holding a copy of the small parts of
baselines/ it edits; a case's `out` folder must not exist afterwards and the
baselines copy must be unchanged unless the case says otherwise.
"""
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile


def tree_digest(root):
    h = hashlib.sha256()
    for dirpath, dirnames, filenames in sorted(os.walk(root)):
        dirnames.sort()
        for name in sorted(filenames):
            p = os.path.join(dirpath, name)
            h.update(os.path.relpath(p, root).encode())
            with open(p, "rb") as f:
                h.update(f.read())
    return h.hexdigest()


class Case:
    def __init__(self, name, tool, args, expect, code=2, setup=None, env=None):
        self.name, self.tool, self.args, self.expect, self.code = name, tool, args, expect, code
        self.setup, self.env = setup, env or {}


def render_shard(shard):
    """A setup that renders one shard of a tiny filter of the ci matrix into r/."""
    def setup(tmp):
        render = os.path.join(os.path.dirname(os.path.abspath(sys.argv[1])), "..", "render", "cavity_render")
        subprocess.run([render, "--matrix", "ci", "--baselines", "baselines", "--shard", shard, "--out", "r",
                        "--filter", "^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$"], cwd=tmp, check=True,
                       capture_output=True)
    return setup


def results_with_null(name, value=None):
    """A setup that runs a one-configuration `cavity run` and writes its
    results.json as NAME with one frame time VALUE (null: a NaN)."""
    def setup(tmp):
        cavity = os.path.abspath(sys.argv[1])
        subprocess.run([cavity, "run", "--kernel", "alchemy", "--frames", "3", "--warmup", "0", "--res", "64x36",
                        "--backend", "vk", "--out", "run"], cwd=tmp, check=True, capture_output=True)
        with open(os.path.join(tmp, "run", "results.json")) as f:
            doc = json.load(f)
        doc["runs"][0]["frame"]["samples_ms"][1] = value
        with open(os.path.join(tmp, name), "w") as f:
            json.dump(doc, f)
        shutil.rmtree(os.path.join(tmp, "run"))
    return setup


def edit_json(rel, change):
    """A setup that loads baselines/REL, applies change(doc) and writes it back as text."""
    def setup(tmp):
        path = os.path.join(tmp, "baselines", rel)
        doc = json.load(open(path))
        text = change(doc)
        with open(path, "w") as f:
            f.write(text if isinstance(text, str) else json.dumps(doc, indent=1))
    return setup


def replace_with_folder(rel):
    def setup(tmp):
        path = os.path.join(tmp, rel)
        if os.path.exists(path):
            os.remove(path)
        os.makedirs(path)
    return setup


BENCH_JSON = ('{"benchmarks": [{"name": "%s/iterations:1/manual_time", "run_type": "iteration", "real_time": %g, '
              '"time_unit": "ms"}]}')
SHARD_JSON = ('{"schema": "cavity.gate/1", "matrix": "ci", "shard": [%d, 2], "strict": %s, "seconds": 1, '
              '"backend_errors": [], "results": []}')


def gzip_cut_short(rel):
    """A setup that writes a gzip-compressed bench JSON without the last 4
    bytes of its trailer (a truncated download)."""
    def setup(tmp):
        import gzip
        data = gzip.compress((BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1)).encode())
        with open(os.path.join(tmp, rel), "wb") as f:
            f.write(data[:-4])
    return setup


def ingested(db, commit, parent):
    """A setup that ingests a one-configuration bench JSON (a.json) as
    COMMIT with PARENT into DB."""
    def setup(tmp):
        write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))(tmp)
        subprocess.run([os.path.abspath(sys.argv[1]), "history", "ingest", "--db", db, "--commit", commit, "--parent",
                        parent, "a.json"], cwd=tmp, check=True, capture_output=True)
    return setup


def write(rel, text):
    def setup(tmp):
        path = os.path.join(tmp, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)
    return setup


def truncate_baseline(tmp):
    folder = os.path.join(tmp, "baselines", "images", "corner", "alchemy", "n16", "b4", "full", "160x90")
    path = os.path.join(folder, "color.png")
    data = open(path, "rb").read()
    with open(path, "wb") as f:
        f.write(data[: len(data) // 2])


def matrix_param_infinity(tmp):
    """baselines/matrices.json with a matrix `inf` whose radius is a bare Infinity (not JSON)."""
    path = os.path.join(tmp, "baselines", "matrices.json")
    with open(path) as f:
        doc = json.load(f)
    doc["inf"] = {"description": "d", "groups": [{"scenes": ["corner"], "kernels": ["alchemy"], "samples": [8],
                                                 "blurs": [4], "resolutions": ["full"], "sizes": ["64x36"],
                                                 "apis": ["vk"], "stages": ["compute"], "params": {"radius": [0.5]}}]}
    with open(path, "w") as f:
        f.write(json.dumps(doc).replace('"radius": [0.5]', '"radius": [Infinity]'))


def manifest_tolerance_1e999(doc):
    text = json.dumps(doc, indent=1)
    return text.replace('"max_abs": 0.5', '"max_abs": 1e999', 1) if '"max_abs": 0.5' in text else \
        re.sub(r'"max_abs": [0-9.e-]+', '"max_abs": 1e999', text, count=1)


def budgets_1e999(doc):
    text = json.dumps(doc, indent=1)
    return re.sub(r'("ao": )[0-9.e-]+', r"\g<1>1e999", text, count=1)


def frames_as_string(doc):
    doc["ci"]["frames"] = "3"


def frames_negative(doc):
    doc["ci"]["frames"] = -1
    doc["ci"]["warmup"] = -5


GATE = ["gate", "--matrix", "ci", "--baselines", "baselines", "--filter", "^corner/alchemy/n16/b4/full/160x90/vk/compute$",
        "--out", "out"]
RUN = ["run", "--backend", "vk", "--res", "32x18", "--frames", "2", "--warmup", "0", "--out", "out"]
LONG = "x" * 4200
ALTERNATION = "|".join(f"c/n{i:05d}" for i in range(12000))   # 108,000 characters, past 100,000 states
FOLDER300 = "y" * 300

CASES = [
    # Files that crashed (exit 134) on main.
    Case("manifest-1e999", "cavity", GATE, ["manifest.json", "1e999"], setup=edit_json("manifest.json", manifest_tolerance_1e999)),
    Case("budgets-1e999", "cavity", GATE, ["budgets.json", "1e999"], setup=edit_json("budgets.json", budgets_1e999)),
    Case("matrices-frames-string", "cavity", GATE, ["matrices.json", "frames", '"3"'],
         setup=edit_json("matrices.json", frames_as_string)),
    Case("manifest-is-folder", "cavity", GATE, ["manifest.json", "folder"], setup=replace_with_folder("baselines/manifest.json")),
    Case("gate-json-folder-update", "cavity", ["baselines", "update", "--baselines", "baselines", "--from", "prev"],
         ["gate.json", "folder"], setup=replace_with_folder("prev/gate.json")),
    # A kernel parameter of integer type is written in digits (16.0 named n16).
    Case("run-int-param-decimal", "cavity", ["run", "--samples", "16.0", "--list"], ["--samples '16.0'", "in digits"]),
    Case("run-int-param-exponent", "cavity", ["run", "--samples", "1e1", "--list"], ["--samples '1e1'", "in digits"]),
    Case("run-float-param-same-32-bit", "cavity", ["run", "--radius", "0.5,0.50000001", "--list"],
         ["--radius", "0.50000001 is a value given twice", "32-bit float of it is 0.5"]),
    # Only a .glsl file is a kernel source; the packages' kernel.toml were offered as candidates.
    Case("kernel-source-toml", "cavity", ["run", "--kernel-source", "kernel.toml=x.glsl", "--list"],
         ["--kernel-source kernel.toml", "no kernel source of that name", "a .glsl file"],
         setup=write("x.glsl", "void cavity_main(ivec2 p) {}\n")),
    Case("matrix-param-infinity", "cavity", ["gate", "--matrix", "inf", "--baselines", "baselines", "--list"],
         ["matrices.json", "radius has null (or a NaN or Infinity)"], setup=matrix_param_infinity),
    # Output files that are folders are found before anything is measured.
    Case("run-results-json-folder", "cavity", RUN[:-1] + ["prev"], ["--out prev", "prev/results.json", "is a folder"],
         setup=replace_with_folder("prev/results.json")),
    Case("gate-summary-folder", "cavity", GATE[:-1] + ["prev"], ["--out prev", "prev/summary.md", "is a folder"],
         setup=replace_with_folder("prev/summary.md")),
    Case("gate-json-folder-merge", "cavity", ["gate", "merge", "prev", "--out", "out"], ["gate.json", "folder"],
         setup=replace_with_folder("prev/gate.json")),
    Case("compare-folder", "cavity", ["compare", "prev", "x.json"], ["prev", "folder"], setup=replace_with_folder("prev")),
    Case("gate-json-wrong-type", "cavity", ["gate", "merge", "prev", "--out", "out"], ["gate.json", "seconds"],
         setup=write("prev/gate.json", '{"schema": "cavity.gate/1", "matrix": "ci", "shard": [0, 1], "seconds": "3", "backend_errors": [], "results": []}')),
    # A merge is the whole matrix's verdict: a shard missing, given twice or
    # gated unlike the others is refused.
    Case("gate-merge-shard-missing", "cavity", ["gate", "merge", "s0", "--out", "out"], ["shards of 2", "missing (1)"],
         setup=write("s0/gate.json", SHARD_JSON % (0, "false"))),
    Case("gate-merge-shard-twice", "cavity", ["gate", "merge", "s0", "s0", "--out", "out"], ["s0", "0/2", "twice"],
         setup=write("s0/gate.json", SHARD_JSON % (0, "false"))),
    Case("gate-merge-out-is-a-shard", "cavity", ["gate", "merge", "s0", "s1", "--out", "./s0"], ["--out ./s0", "a shard merged"],
         setup=lambda tmp: (write("s0/gate.json", SHARD_JSON % (0, "false"))(tmp),
                            write("s1/gate.json", SHARD_JSON % (1, "false"))(tmp))),
    Case("gate-merge-strict-mixed", "cavity", ["gate", "merge", "s0", "s1", "--out", "out"], ["s1", "--strict"],
         setup=lambda tmp: (write("s0/gate.json", SHARD_JSON % (0, "false"))(tmp),
                            write("s1/gate.json", SHARD_JSON % (1, "true"))(tmp))),
    # Too small for the pyramid's mip levels: said before any image is made
    # (it was the API's error: exit 4 on GL, 2 on Vulkan).
    Case("res-under-pyramid", "cavity", ["run", "--kernel", "alchemy_fast", "--res", "8x8", "--backend", "gl", "--out", "out"],
         ["--res", "8x8", "at least 16 px"]),
    Case("res-under-pyramid-half", "cavity", ["run", "--kernel", "alchemy_fast", "--res", "16x9", "--resolution", "half", "--out", "out"],
         ["--res", "16x9", "at least 31 px", "half"]),
    # Bad values that were accepted.
    Case("samples-empty", "cavity", RUN + ["--samples", ""], ["--samples", "empty"]),
    Case("samples-empty-item", "cavity", RUN + ["--samples", "8,,16"], ["--samples", "empty"]),
    Case("samples-duplicate-item", "cavity", RUN + ["--samples", "8,8"], ["--samples", "8", "twice"]),
    Case("flag-twice", "cavity", RUN + ["--samples", "8", "--samples", "16"], ["--samples", "twice"]),
    Case("gate-filter-nomatch", "cavity", GATE[:-4] + ["--filter", "nomatch", "--out", "out"], ["--filter", "nomatch", "matches none"]),
    # A repeated group that repeats itself: std::regex backtracks for minutes on a miss.
    Case("gate-filter-nested-repeat", "cavity", GATE[:-4] + ["--filter", "(.*)*zzz", "--out", "out"],
         ["--filter", "(.*)*", "repeats a group"]),
    Case("run-filter-nested-repeat", "cavity", RUN + ["--filter", "(a+)+zzz"], ["--filter", "(a+)+", "repeats a group"]),
    Case("matrices-negative-frames", "cavity", GATE, ["matrices.json", "frames", "-1"], setup=edit_json("matrices.json", frames_negative)),
    Case("bench-iterations-0", "cavity_bench", ["--iterations", "0"], ["--iterations", "0"]),
    Case("bench-iterations-abc", "cavity_bench", ["--iterations", "abc"], ["--iterations", "abc"]),
    Case("bench-iterations-neg", "cavity_bench", ["--iterations", "-3"], ["--iterations", "-3"]),
    Case("bench-warmup-abc", "cavity_bench", ["--warmup", "abc"], ["--warmup", "abc"]),
    Case("bench-device-abc", "cavity_bench", ["--device", "abc"], ["--device", "abc"]),
    Case("bench-filter-bad-regex", "cavity_bench", ["--benchmark_filter=("], ["--benchmark_filter", "("]),
    Case("bench-filter-empty", "cavity_bench", ["--benchmark_filter="], ["--benchmark_filter", "empty"]),
    Case("bench-repetitions-neg", "cavity_bench", ["--benchmark_repetitions=-1"], ["--benchmark_repetitions", "-1"]),
    Case("bench-repetitions-0", "cavity_bench", ["--benchmark_repetitions=0"], ["--benchmark_repetitions", "0"]),
    Case("bench-flag-twice", "cavity_bench", ["--benchmark_repetitions=1", "--benchmark_repetitions=2"],
         ["--benchmark_repetitions", "twice"]),
    Case("bench-min-time-negative", "cavity_bench", ["--benchmark_min_time=-1"], ["--benchmark_min_time", "-1"]),
    Case("bench-min-time-word", "cavity_bench", ["--benchmark_min_time=abc"], ["--benchmark_min_time", "abc"]),
    Case("bench-repetitions-abc", "cavity_bench", ["--benchmark_repetitions=abc"], ["--benchmark_repetitions", "abc"]),
    Case("bench-out-format-xml", "cavity_bench", ["--benchmark_out_format=xml"], ["--benchmark_out_format", "xml", "json"]),
    Case("radius-underflow", "cavity", RUN + ["--radius", "1e-300"], ["--radius", "1e-300"]),
    Case("depth-sigma-underflow", "cavity", RUN + ["--blur", "4", "--depth_sigma", "1e-30"], ["--depth_sigma", "1e-30"]),
    Case("compare-empty-samples", "cavity", ["compare", "a.json", "b.json"], ["a.json", "samples_ms"],
         setup=lambda tmp: [write(n, json.dumps({"schema": "cavity.results/1", "runs": [{"id": "x", "clock": "gpu-timestamp", "frame": {"samples_ms": []},
                                                           "passes": []}]}))(tmp) for n in ("a.json", "b.json")]),
    Case("compare-unknown-clock", "cavity", ["compare", "a.json", "a.json"], ["a.json", "clock 'sundial'", "gpu-timestamp or wall"],
         setup=write("a.json", json.dumps({"schema": "cavity.results/1", "runs": [
             {"id": "x", "clock": "sundial", "frame": {"samples_ms": [1.0, 1.1]}, "passes": []}]}))),
    # Late or multi-line.
    Case("out-proc", "cavity", RUN[:-2] + ["--out", "/proc/x"], ["--out", "/proc/x"]),
    Case("out-too-long", "cavity", RUN[:-2] + ["--out", LONG], ["--out", "too long"]),
    Case("out-long-component", "cavity", RUN[:-2] + ["--out", FOLDER300], ["--out", "too long"]),
    Case("truncated-baseline", "cavity", GATE, ["color.png"], setup=truncate_baseline),
    Case("gl-device-out-of-range", "cavity", ["run", "--backend", "gl", "--device", "5", "--res", "32x18", "--out", "out"],
         ["--device", "5"], code=3),
    # Weak messages.
    Case("not-a-number-says-range", "cavity", RUN + ["--radius", "abc"], ["--radius", "abc", "in"]),
    Case("nan", "cavity", RUN + ["--radius", "nan"], ["--radius", "nan", "in"]),
    Case("inf", "cavity", RUN + ["--radius", "inf"], ["--radius", "inf", "in"]),
    Case("hexfloat", "cavity", RUN + ["--radius", "0x1p-2"], ["--radius", "0x1p-2", "in"]),
    # A parameter no kernel of the selection reads: named, with who reads it.
    Case("param-nobody-reads", "cavity", RUN + ["--kernel", "alchemy", "--ssdo_mode", "radiance"],
         ["--ssdo_mode", "no kernel of the selection reads it", "ssdo"]),
    Case("param-read-at-half", "cavity", RUN + ["--kernel", "alchemy", "--fused_tail", "1"],
         ["--fused_tail", "--resolution half"]),
    Case("out-empty", "cavity", RUN[:-2] + ["--out", ""], ["--out", "empty"]),
    Case("stray-argument", "cavity", ["run", "stray"], ["stray"]),
    # More of the same families.
    Case("budgets-is-folder", "cavity", GATE, ["budgets.json", "folder"], setup=replace_with_folder("baselines/budgets.json")),
    Case("matrices-missing", "cavity", GATE, ["matrices.json"], setup=lambda tmp: os.remove(os.path.join(tmp, "baselines", "matrices.json"))),
    Case("matrices-samples-fraction", "cavity", GATE, ["matrices.json", "samples", "16.5"],
         setup=edit_json("matrices.json", lambda d: d["ci"]["groups"][0].__setitem__("samples", [16.5]))),
    Case("manifest-not-json", "cavity", GATE, ["manifest.json", "line 1"], setup=write("baselines/manifest.json", "{oops")),
    Case("compare-missing", "cavity", ["compare", "a.json", "b.json"], ["a.json", "no such file"]),
    Case("gbuffer-file-folder", "cavity", RUN + ["--gbuffer", "import", "--gbuffer-file", "prev"], ["prev"],
         setup=replace_with_folder("prev")),
    Case("res-zero", "cavity", RUN[:3] + ["--res", "0x0", "--out", "out"], ["--res", "0x0"]),
    Case("frames-1e999", "cavity", RUN[:5] + ["--frames", "1e999", "--out", "out"], ["--frames", "1e999"]),
    Case("max-noise-nan", "cavity", RUN + ["--max-noise", "nan"], ["--max-noise", "nan"]),
    Case("unknown-flag", "cavity", RUN + ["--radiuss", "1"], ["--radiuss", "unknown"]),
    Case("gate-out-is-file", "cavity", GATE[:-1] + ["prev"], ["--out", "prev", "not a folder"], setup=write("prev", "x")),
    Case("bench-plant-file-folder", "cavity_bench", ["--plant-file", "prev"], ["--plant-file", "prev"],
         setup=replace_with_folder("prev")),
    Case("bench-frames-1e999", "cavity_bench", ["--frames", "1e999"], ["--frames", "1e999"]),
    # Plants that would plant nothing (cavity_bench's timing-verdict check).
    Case("bench-plant-unknown-pass", "cavity_bench", ["--plant", "nopass:300"], ["--plant", "nopass", "passes:"]),
    Case("bench-plant-file-array", "cavity_bench", ["--plant-file", "p.json"], ["--plant-file", "p.json", "array"],
         setup=write("p.json", "[1, 2]")),
    Case("bench-plant-file-unknown-id", "cavity_bench", ["--plant-file", "p.json"], ["--plant-file", "nosuch/id", "not in the sweep"],
         setup=write("p.json", '{"nosuch/id": {"ao": 5}}')),
    Case("bench-plant-and-file", "cavity_bench", ["--plant", "ao:5", "--plant-file", "p.json"], ["--plant", "--plant-file"],
         setup=write("p.json", '{"x": {"ao": 5}}')),
    # An edited kernel (--kernel-source) that cannot be read or would change nothing.
    Case("bench-kernel-source-no-equals", "cavity_bench", ["--kernel-source", "ssao_alchemy_fast.glsl"],
         ["--kernel-source", "ssao_alchemy_fast.glsl", "NAME=FILE"]),
    Case("bench-kernel-source-folder", "cavity_bench", ["--kernel-source", "ssao_alchemy_fast.glsl=prev"],
         ["--kernel-source", "prev"], setup=replace_with_folder("prev")),
    Case("bench-kernel-source-unused", "cavity_bench", ["--kernel-source", "composite_ssdo.glsl=k.glsl",
                                                        "--benchmark_filter=/alchemy_fast/"],
         ["--kernel-source", "composite_ssdo.glsl", "change nothing"], setup=write("k.glsl", "void main() {}\n")),
    # A run that measured nothing (or part of what it was asked) never exits 0.
    Case("bench-kernel-source-broken", "cavity_bench",
         ["--kernel-source", "ssao_alchemy_fast.glsl=k.glsl", "--frames", "1", "--warmup", "0",
          "--benchmark_filter=^corner/alchemy_fast/n16/b4/full/320x180/vk/compute"],
         ["measured nothing", "k.glsl"], setup=write("k.glsl", "void cavity_main(ivec2 pixel) { not glsl }\n")),
    # ... and leaves an existing --benchmark_out file as it was (baselines/ is
    # checked unchanged, so no partial file may stay beside it either).
    Case("bench-failed-run-keeps-out-file", "cavity_bench",
         ["--kernel-source", "ssao_alchemy_fast.glsl=k.glsl", "--frames", "1", "--warmup", "0",
          "--benchmark_out=baselines/keep.json",
          "--benchmark_filter=^corner/alchemy_fast/n16/b4/full/320x180/vk/compute"],
         ["measured nothing", "k.glsl"],
         setup=lambda tmp: (write("k.glsl", "void cavity_main(ivec2 pixel) { not glsl }\n")(tmp),
                            write("baselines/keep.json", "{}\n")(tmp))),
    Case("bench-workgroup-env", "cavity_bench",
         ["--frames", "1", "--warmup", "0", "--benchmark_filter=^corner/alchemy_fast/n16/b4/full/320x180/vk/compute"],
         ["CAVITY_WORKGROUP", "abc"], env={"CAVITY_WORKGROUP": "abc"}),
    Case("run-workgroup-env", "cavity", ["run", "--kernel", "alchemy", "--frames", "1", "--out", "out"],
         ["cavity run: CAVITY_WORKGROUP=abc", "powers of two"], env={"CAVITY_WORKGROUP": "abc"}),
    Case("gate-workgroup-env", "cavity", ["gate", "--matrix", "smoke", "--baselines", "baselines", "--out", "out"],
         ["cavity gate: CAVITY_WORKGROUP=7x9"], env={"CAVITY_WORKGROUP": "7x9"}),
    Case("gate-judge-one-shard-of-two", "cavity", ["gate", "judge", "r", "--baselines", "baselines", "--out", "out"],
         ["shards 1/2", "0/2 are missing", "--shards 1/2"], setup=render_shard("1/2")),
    Case("gate-judge-shard-twice", "cavity", ["gate", "judge", "r", "--shards", "1,1/2", "--baselines", "baselines", "--out", "out"],
         ["--shards 1,1/2", "shard 1 given twice"], setup=render_shard("1/2")),
    Case("approvals-device-class-not-a-class", "cavity", ["gate", "--matrix", "smoke", "--baselines", "baselines", "--out", "out"],
         ["approvals.json", "device_class", "nvidia-h200"],
         setup=edit_json("approvals.json", lambda d: d["approvals"][0].update(device_class="NVIDIA H200/PCIe"))),
    Case("approvals-api-metal", "cavity", ["gate", "--matrix", "smoke", "--baselines", "baselines", "--out", "out"],
         ["approvals.json", "api", "gl or vk"],
         setup=edit_json("approvals.json", lambda d: d["approvals"][0].update(api="metal"))),
    Case("history-ingest-null-sample", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "abcd1234", "bad.json"],
         ["bad.json", "samples_ms", "null"], setup=results_with_null("bad.json")),
    # A time past any pass's (about three hours) was never measured.
    Case("history-ingest-huge-sample", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "abcd1234", "bad.json"],
         ["bad.json", "samples_ms", "1000000000000"], setup=results_with_null("bad.json", 1e12)),
    Case("bench-out-no-folder", "cavity_bench", ["--benchmark_out=nosuch/x.json"], ["--benchmark_out=nosuch/x.json", "does not exist"]),
    Case("bench-out-folder", "cavity_bench", ["--benchmark_out=prev"], ["--benchmark_out=prev", "is a folder"],
         setup=replace_with_folder("prev")),
    Case("compare-nan-real-time", "cavity", ["compare", "a.json", "a.json"], ["a.json", "real_time", "NaN"],
         setup=write("a.json", '{"benchmarks": [{"name": "corner/alchemy/n16/b4/full/32x18/vk/compute", '
                               '"run_type": "iteration", "real_time": NaN, "time_unit": "ms"}]}')),
    Case("compare-negative-real-time", "cavity", ["compare", "a.json", "a.json"], ["a.json", "real_time", "-5", ">= 0"],
         setup=write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", -5))),
    Case("compare-same-file", "cavity", ["compare", "a.json", "./a.json"], ["./a.json", "the same file as a.json"],
         setup=write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 5))),
    # The verdicts over a file compared lost that run; a device never ends.
    Case("compare-json-over-input", "cavity", ["compare", "a.json", "b.json", "--json", "./b.json"],
         ["--json ./b.json", "a file compared"],
         setup=lambda tmp: (write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))(tmp),
                            write("b.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 2))(tmp))),
    Case("compare-device", "cavity", ["compare", "/dev/zero", "a.json"], ["/dev/zero", "device"],
         setup=write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))),
    # A pattern of 100,000 characters overflowed std::regex's stack (a segfault).
    Case("filter-too-long", "cavity", RUN + ["--filter", "a" * 100000, "--list"], ["--filter", "100000 characters",
                                                                                     "an alternative of 100000"]),
    Case("bench-filter-too-long", "cavity_bench", ["--benchmark_filter=" + "a" * 100000, "--benchmark_list_tests"],
         ["--benchmark_filter", "100000 characters"]),
    # An alternation of many short ids is taken up to std::regex's own limit.
    Case("bench-filter-past-state-limit", "cavity_bench", ["--benchmark_filter=" + ALTERNATION, "--benchmark_list_tests"],
         ["--benchmark_filter", "not a regular expression std::regex takes"]),
    # all and gl ran the GL configurations twice under one id.
    Case("backend-all-and-gl", "cavity", ["run", "--backend", "all,gl", "--list"], ["--backend", "all,gl", "give it alone"]),
    # Nothing in common is nothing compared: no verdict, not "0 slower".
    Case("compare-nothing-in-common", "cavity", ["compare", "a.json", "b.json", "--fail-on-slower"],
         ["a.json", "b.json", "no configuration"],
         setup=lambda tmp: (write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))(tmp),
                            write("b.json", BENCH_JSON % ("corner/alchemy/n8/b4/full/32x18/vk/compute", 1))(tmp))),
    # The history's order comes from --parent: no commit is its own parent
    # or comes after its own child.
    Case("history-parent-self", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "beef0001", "--parent",
                                           "beef0001", "a.json"], ["--parent", "beef0001", "own parent"],
         setup=write("a.json", BENCH_JSON % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))),
    Case("history-parent-cycle", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "abcdef1234", "--parent",
                                            "1234abcd", "a.json"], ["--parent", "1234abcd", "descends from"],
         setup=ingested("h.sqlite", "1234abcd", "abcdef1234")),
    Case("history-date-unreadable", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "beef0001", "a.json"],
         ["a.json", "garbage", "ISO 8601"],
         setup=write("a.json", BENCH_JSON.replace('{"benchmarks"', '{"context": {"date": "garbage"}, "benchmarks"')
                     % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))),
    Case("history-clock-bogus", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "beef0001", "a.json"],
         ["a.json", "clock", "bogus"],
         setup=write("a.json", BENCH_JSON.replace('"time_unit"', '"label": "clock=bogus", "time_unit"')
                     % ("corner/alchemy/n16/b4/full/32x18/vk/compute", 1))),
    Case("history-gz-cut-short", "cavity", ["history", "ingest", "--db", "h.sqlite", "--commit", "beef0001", "a.json.gz"],
         ["a.json.gz", "cut short"], setup=gzip_cut_short("a.json.gz")),
    # A value just past a bound is printed as given, not rounded onto it.
    Case("radius-past-float", "cavity", ["run", "--kernel", "alchemy", "--radius", "3.4028236e38", "--list"],
         ["--radius 3.4028236e+38", "<= 100"]),
    # A matrix list that selects nothing, or names a value twice.
    Case("matrix-empty-samples", "cavity", ["gate", "--matrix", "ci", "--baselines", "baselines", "--list"],
         ["matrices.json", "ci.groups[0].samples is empty"],
         setup=edit_json("matrices.json", lambda d: d["ci"]["groups"][0].update(samples=[]))),
    Case("matrix-samples-twice", "cavity", ["gate", "--matrix", "ci", "--baselines", "baselines", "--list"],
         ["matrices.json", "samples has 4 twice"],
         setup=edit_json("matrices.json", lambda d: d["ci"]["groups"][0].update(samples=[4, 4.0]))),
    # Reports and new images beside the references would mix with them.
    Case("gate-out-is-baselines", "cavity", GATE[:-2] + ["--out", "baselines"], ["--out", "baselines", "is the baselines folder"]),
    Case("gate-out-in-baselines", "cavity", GATE[:-2] + ["--out", "baselines/out"],
         ["--out", "baselines/out", "is inside the baselines folder"]),
    # The image store (docs/store.md).
    Case("store-is-file", "cavity", GATE + ["--store", "prev"], ["--store", "prev", "not a folder"], setup=write("prev", "x")),
    Case("store-empty", "cavity", GATE + ["--store", ""], ["--store", "empty"]),
    # A variable set to a space is a mistake, not a folder named " ".
    Case("store-env-blank", "cavity", GATE, ["CAVITY_STORE", "' '", "blank"], env={"CAVITY_STORE": " "}),
    Case("store-cache-env-blank", "cavity", GATE + ["--store", "http://127.0.0.1:9/x"], ["CAVITY_STORE_CACHE", "blank"],
         env={"CAVITY_STORE_CACHE": " "}),
    Case("store-scheme", "cavity", GATE + ["--store", "s3://bucket/x"], ["--store", "s3://bucket/x", "unknown scheme"]),
    Case("store-credentials-in-url", "cavity", ["store", "check", "--baselines", "baselines", "--store",
                                                "https://u:secret@example.invalid/x"], ["--store", "credentials in the URL"]),
    Case("store-check-no-match", "cavity", ["store", "check", "--baselines", "baselines", "--class", "no-such-gpu"],
         ["no-such-gpu", "approvals.json"]),
    # The barrier switches (docs/synchronisation.md): checked before anything is written.
    Case("no-barriers-yes", "cavity", RUN, ["CAVITY_NO_BARRIERS=yes", "must be 0 or 1"], env={"CAVITY_NO_BARRIERS": "yes"}),
    Case("both-barrier-switches", "cavity", RUN, ["CAVITY_FULL_BARRIERS and CAVITY_NO_BARRIERS"],
         env={"CAVITY_NO_BARRIERS": "1", "CAVITY_FULL_BARRIERS": "1"}),
    Case("quality-full-barriers-2", "cavity", ["quality", "--res", "32x18", "--out", "out"], ["CAVITY_FULL_BARRIERS=2"],
         env={"CAVITY_FULL_BARRIERS": "2"}),
    Case("quality-param-list", "cavity", ["quality", "--kernel", "hemisphere_fast", "--steps", "4,8", "--list"],
         ["--steps", "4,8", "one value"]),
    Case("gl-force-glsl-bogus", "cavity", RUN, ["CAVITY_GL_FORCE_GLSL=yes", "0 or 1"],
         env={"CAVITY_GL_FORCE_GLSL": "yes"}),
    Case("bench-no-barriers-nan", "cavity_bench", ["--benchmark_filter=timer/empty_scope"], ["CAVITY_NO_BARRIERS=nan"],
         env={"CAVITY_NO_BARRIERS": "nan"}),
    Case("store-missing-object", "cavity", ["store", "check", "--baselines", "baselines", "--store", "prev"],
         ["store prev", "no object"], code=5, setup=replace_with_folder("prev")),
]


def run_case(c, tools, source):
    with tempfile.TemporaryDirectory() as tmp:
        shutil.copytree(os.path.join(source, "baselines"), os.path.join(tmp, "baselines"),
                        ignore=lambda d, names: [n for n in names if n == "images" and d.endswith("baselines")])
        # One baseline folder (the one the gate cases judge) is enough.
        sub = os.path.join("images", "corner", "alchemy", "n16", "b4", "full", "160x90")
        shutil.copytree(os.path.join(source, "baselines", sub), os.path.join(tmp, "baselines", sub))
        if c.setup:
            c.setup(tmp)
        before = tree_digest(os.path.join(tmp, "baselines")) if os.path.isdir(os.path.join(tmp, "baselines")) else None
        env = dict(os.environ, **c.env)
        try:
            r = subprocess.run([tools[c.tool]] + c.args, cwd=tmp, capture_output=True, text=True, env=env, timeout=300)
        except subprocess.TimeoutExpired:
            return "timed out"
        lines = [l for l in r.stderr.splitlines() if l.strip()]
        problems = []
        if r.returncode != c.code:
            problems.append(f"exit {r.returncode}, expected {c.code}")
        if len(lines) != 1:
            problems.append(f"{len(lines)} lines on stderr")
        missing = [e for e in c.expect if e not in r.stderr]
        if missing:
            problems.append(f"message lacks {missing}")
        # Exit 3 still records the error in out/results.json (README "Exit codes").
        if c.code == 2 and os.path.exists(os.path.join(tmp, "out")):
            problems.append("wrote out/")
        if before is not None and os.path.isdir(os.path.join(tmp, "baselines")) and \
                tree_digest(os.path.join(tmp, "baselines")) != before:
            problems.append("changed baselines/")
        if problems:
            return "; ".join(problems) + f"\n      stderr: {r.stderr.strip()[:600]!r}"
        return None


def main():
    tools = {"cavity": os.path.abspath(sys.argv[1]), "cavity_bench": os.path.abspath(sys.argv[2])}
    source = os.path.abspath(sys.argv[3])
    only = re.compile(sys.argv[4]) if len(sys.argv) > 4 else None
    failed = 0
    for c in CASES:
        if only and not only.search(c.name):
            continue
        problem = run_case(c, tools, source)
        print(f"{'FAIL' if problem else 'ok  '} {c.name}" + (f": {problem}" if problem else ""))
        failed += bool(problem)
    print(f"{failed} of {len(CASES)} cases failed")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
