#!/usr/bin/env python3
"""Tests for scripts/charts/charts.py and its package, scripts/charts/cavity_charts/,
and the table scripts beside them (floor_table.py).

    python3 -m unittest scripts/charts/test_charts.py
    python3 scripts/charts/test_charts.py

Drawing needs matplotlib (Debian's python3-matplotlib); charts.py re-runs
itself under /usr/bin/python3 when the python3 on PATH lacks it, so these
tests run from either. Every chart kind is drawn from the small synthetic
files in testdata/ and from copies of real H100 and H200 runs kept there too
(stored gzip, X.json.gz; the large ones cut to the configurations the tests
use): the folder needs nothing outside it.
"""

import gzip
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TESTDATA = os.path.join(HERE, "testdata")
CHARTS = os.path.join(HERE, "charts.py")
SAMPLE = os.path.join(TESTDATA, "sample_benchmark.json")
SAMPLE_OLD = os.path.join(TESTDATA, "sample_benchmark_old.json")
SWEEPS = [os.path.join(TESTDATA, n) for n in ("2026-11-24_h100_full_sweep.json.gz", "2026-11-30_h200_full_sweep.json.gz")]
QUALITY_COST = os.path.join(TESTDATA, "2026-12-02_h200_quality_cost")
FLOOR3 = os.path.join(TESTDATA, "2026-12-02_h200_floor3")
FLOOR_LIFT = os.path.join(FLOOR3, "lift.json.gz")
SHADER_STATS = os.path.join(TESTDATA, "2026-12-03_h200_shader_stats")
SINGLE_FILE_CHARTS = ("time_vs_samples", "time_vs_blur", "full_vs_half", "time_vs_megapixels",
                      "gl_vs_vk", "compute_vs_fragment", "passes")

sys.path.insert(0, HERE)
import charts  # noqa: E402  (pure functions only; matplotlib is imported when drawing)
import cavity_json  # noqa: E402
from cavity_charts import cli  # noqa: E402


def run_charts(*args):
    return subprocess.run([sys.executable, CHARTS, *args], capture_output=True, text=True, timeout=300)


class ParseId(unittest.TestCase):
    def test_plain_id(self):
        c = charts.parse_id("corner/alchemy/n16/b4/full/1920x1080/vk/compute")
        self.assertEqual(c, {"scene": "corner", "kernel": "alchemy", "samples": 16, "blur": 4, "params": "",
                             "res": "full", "size": (1920, 1080), "api": "vk", "stage": "compute"})

    def test_kernel_parameters_stay_in_the_configuration(self):
        # Two configurations that differ only in a kernel's own parameter are
        # two configurations (they were merged into one, samples and all).
        a = charts.parse_id("corner/hbao/n16/b0/directions=2/attenuation=none/full/160x90/vk/compute/manual_time")
        b = charts.parse_id("corner/hbao/n16/b0/directions=8/attenuation=none/full/160x90/vk/compute/manual_time")
        self.assertEqual(a["params"], "directions=2/attenuation=none")
        self.assertNotEqual(charts.config_id(a), charts.config_id(b))
        self.assertEqual(charts.config_id(b), "corner/hbao/n16/b0/directions=8/attenuation=none/full/160x90/vk/compute")

    def test_manual_time_and_iterations(self):
        for name in ("corner/alchemy/n16/b4/full/1920x1080/vk/compute/manual_time",
                     "corner/alchemy/n16/b4/full/1920x1080/vk/compute/iterations:50/manual_time",
                     "corner/alchemy/n16/b4/full/1920x1080/vk/compute/iterations:50/repeats:3/manual_time"):
            c = charts.parse_id(name)
            self.assertIsNotNone(c, name)
            self.assertEqual(charts.config_id(c), "corner/alchemy/n16/b4/full/1920x1080/vk/compute")

    def test_aggregate_suffixes(self):
        for suffix in ("_median", "_mean", "_stddev", "_cv"):
            for base in ("slats/ssdo/n8/b0/half/320x180/gl/fragment",
                         "slats/ssdo/n8/b0/half/320x180/gl/fragment/manual_time",
                         "slats/ssdo/n8/b0/half/320x180/gl/fragment/iterations:50/manual_time"):
                c = charts.parse_id(base + suffix)
                self.assertIsNotNone(c, base + suffix)
                self.assertEqual(charts.config_id(c), "slats/ssdo/n8/b0/half/320x180/gl/fragment")
        # a custom aggregate, named by the entry's aggregate_name
        c = charts.parse_id("corner/alchemy/n16/b4/full/1920x1080/vk/compute/manual_time_p90", None, "p90")
        self.assertEqual(charts.config_id(c), "corner/alchemy/n16/b4/full/1920x1080/vk/compute")

    def test_counters_fallback(self):
        counters = {"samples": 32.0, "blur": 2.0, "half": 1.0, "fragment": 0.0, "width": 640.0, "height": 360.0}
        c = charts.parse_id("corner/hemisphere/vk/manual_time", counters)
        self.assertEqual(charts.config_id(c), "corner/hemisphere/n32/b2/half/640x360/vk/compute")
        self.assertIsNone(charts.parse_id("BM_Something/8", {}))


class Computations(unittest.TestCase):
    def setUp(self):
        self.records = list(charts.load_results(SAMPLE)["records"].values())
        with open(SAMPLE) as f:
            self.raw = json.load(f)["benchmarks"]

    def raw_median(self, cid):
        """The chart's time for an id, read independently from the raw JSON."""
        entries = [e for e in self.raw if e["run_name"].startswith(cid + "/")]
        med = [e for e in entries if e.get("aggregate_name") == "median"]
        use = med or [e for e in entries if e["run_type"] == "iteration"]
        return sum(e["real_time"] for e in use) / len(use)

    def test_median_preferred(self):
        cid = "corner/alchemy/n16/b4/full/1920x1080/vk/compute"
        rec = charts.load_results(SAMPLE)["records"][cid]
        med = [e["real_time"] for e in self.raw if e["name"].startswith(cid) and e.get("aggregate_name") == "median"]
        self.assertEqual(len(med), 1)
        self.assertAlmostEqual(rec["ms"], med[0])

    def test_speedups_are_full_over_half(self):
        sp = charts.speedups(self.records)
        self.assertGreaterEqual(len(sp), 3)
        for (kernel, api), (full, half, entry) in sp.items():
            full, half, ratio = full["ms"], half["ms"], entry["ratio"]
            fid = f"corner/{kernel}/n16/b4/full/1920x1080/{api}/compute"
            hid = f"corner/{kernel}/n16/b4/half/1920x1080/{api}/compute"
            self.assertAlmostEqual(full, self.raw_median(fid))
            self.assertAlmostEqual(half, self.raw_median(hid))
            self.assertAlmostEqual(ratio, self.raw_median(fid) / self.raw_median(hid))
            self.assertGreater(ratio, 1.5)

    def test_format_ratio(self):
        self.assertEqual(charts.format_ratio(2.66), "2.7x")
        self.assertEqual(charts.format_ratio(1.0), "1.0x")
        self.assertEqual(charts.format_ratio(30.4), "30x")

    def test_fit_through_origin(self):
        slope, r2 = charts.fit_through_origin([1, 2, 4], [0.5, 1.0, 2.0])
        self.assertAlmostEqual(slope, 0.5)
        self.assertAlmostEqual(r2, 1.0)

    def test_device_line(self):
        ctx = {"cavity_device": "gl: NVIDIA H100 80GB HBM3; vk: NVIDIA H100 80GB HBM3"}
        self.assertEqual(charts.device_line(ctx), "NVIDIA H100 80GB HBM3")
        self.assertTrue(charts.is_compute_card(ctx))
        self.assertFalse(charts.is_compute_card({"cavity_device": "vk: llvmpipe (LLVM 15.0.6, 256 bits)"}))


class Command(unittest.TestCase):
    def test_all_charts(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "charts")
            r = run_charts(SAMPLE_OLD, SAMPLE, "--out", out, "--title", "Cavity test")
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "index.json")) as f:
                index = json.load(f)
            names = [c["name"] for c in index["charts"]]
            self.assertEqual(names, list(SINGLE_FILE_CHARTS) + ["history"])
            printed = set(r.stdout.split())
            for c in index["charts"]:
                self.assertTrue(c["title"].startswith("Cavity test: "), c["title"])
                for kind in ("png", "svg"):
                    path = os.path.join(out, c[kind])
                    self.assertTrue(os.path.isfile(path), path)
                    self.assertGreater(os.path.getsize(path), 1000, path)
                    self.assertIn(path, printed)
                with open(os.path.join(out, c["png"]), "rb") as f:
                    self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
                with open(os.path.join(out, c["svg"])) as f:
                    self.assertIn("<svg", f.read(2000))

            # the speed-ups written on full_vs_half are full/half from the data
            records = list(charts.load_results(SAMPLE)["records"].values())
            expected = {charts.series_label(k): charts.format_ratio(v[2]["ratio"])
                        for k, v in charts.speedups(records).items()}
            entry = next(c for c in index["charts"] if c["name"] == "full_vs_half")
            self.assertEqual(entry["labels"], expected)
            with open(os.path.join(out, "full_vs_half.svg")) as f:
                svg = f.read()
            written = re.findall(r">\s*(\d+(?:\.\d)?x)\s*<", svg)  # text is kept as text (svg.fonttype none)
            self.assertEqual(sorted(written), sorted(expected.values()))
            for label, text in expected.items():
                kernel, api = label.split(" · ")
                api = {"Vulkan": "vk", "OpenGL": "gl"}[api]
                full = next(r for r in records if r["id"] == f"corner/{kernel}/n16/b4/full/1920x1080/{api}/compute")
                half = next(r for r in records if r["id"] == f"corner/{kernel}/n16/b4/half/1920x1080/{api}/compute")
                self.assertEqual(text, charts.format_ratio(full["ms"] / half["ms"]))

            # fragment bars are flagged on an H100
            with open(os.path.join(out, "compute_vs_fragment.svg")) as f:
                self.assertIn("fragment (non-representative on H100)", f.read())

    def test_single_file_skips_history(self):
        with tempfile.TemporaryDirectory() as tmp:
            r = run_charts(SAMPLE, "--out", tmp)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(tmp, "index.json")) as f:
                index = json.load(f)
            self.assertEqual([c["name"] for c in index["charts"]], list(SINGLE_FILE_CHARTS))
            self.assertEqual([s["name"] for s in index["skipped"]], ["history"])
            self.assertIn("skipped history", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(tmp, "history.png")))

    def test_missing_axes_are_skipped(self):
        # only a sample sweep: every chart but time_vs_samples lacks its axis
        with open(SAMPLE) as f:
            data = json.load(f)
        data["benchmarks"] = [e for e in data["benchmarks"]
                              if re.match(r"corner/alchemy/n\d+/b4/full/1920x1080/vk/compute/", e["name"])]
        with tempfile.TemporaryDirectory() as tmp:
            src = os.path.join(tmp, "samples_only.json")
            with open(src, "w") as f:
                json.dump(data, f)
            out = os.path.join(tmp, "out")
            r = run_charts(src, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "index.json")) as f:
                index = json.load(f)
            self.assertEqual([c["name"] for c in index["charts"]], ["time_vs_samples", "passes"])
            self.assertEqual(sorted(os.listdir(out)), ["index.json", "passes.png", "passes.svg", "time_vs_samples.png",
                                                       "time_vs_samples.svg"])

    def check_bad(self, content, expect):
        with tempfile.TemporaryDirectory() as tmp:
            bad = os.path.join(tmp, "results.json")
            with open(bad, "w") as f:
                f.write(content)
            out = os.path.join(tmp, "out")
            # a good file first: nothing is written even though it alone would chart
            r = run_charts(SAMPLE, bad, "--out", out)
            self.assertEqual(r.returncode, 2)
            lines = r.stderr.strip().splitlines()
            self.assertEqual(len(lines), 1, r.stderr)
            self.assertTrue(lines[0].startswith(f"charts: {bad}: "), lines[0])
            self.assertIn(expect, lines[0])
            self.assertEqual(r.stdout, "")
            self.assertFalse(os.path.exists(out))

    def test_not_benchmark_json(self):
        self.check_bad('{"runs": []}', "neither Google Benchmark JSON (no 'benchmarks' list) nor a cavity results.json")

    def test_not_json(self):
        self.check_bad("corner/alchemy/n16 0.09 ms\n", "not JSON")

    def test_entry_without_time(self):
        self.check_bad('{"context": {}, "benchmarks": [{"name": "corner/alchemy/n16/b4/full/1920x1080/vk/compute"}]}',
                       "has no numeric 'real_time'")

    def test_entry_without_name(self):
        self.check_bad('{"context": {}, "benchmarks": [{"real_time": 1.0}]}', "has no 'name'")

    def test_missing_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "out")
            missing = os.path.join(tmp, "nope.json")
            r = run_charts(missing, "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1)
            self.assertIn(f"charts: {missing}: cannot read", r.stderr)
            self.assertFalse(os.path.exists(out))


class Package(unittest.TestCase):
    """charts.py is the command line of cavity_charts/: --help names every chart and
    subcommand, and every chart kind draws from committed (gzip) results."""

    def check_index(self, out, names):
        with open(os.path.join(out, "index.json")) as f:
            index = json.load(f)
        self.assertEqual([c["name"] for c in index["charts"]], list(names))
        for c in index["charts"]:
            for kind in ("png", "svg"):
                self.assertGreater(os.path.getsize(os.path.join(out, c[kind])), 1000)
        return index

    def test_help_lists_every_subcommand(self):
        r = run_charts("--help")
        self.assertEqual(r.returncode, 0, r.stderr)
        for name in cli.CHART_NAMES + ("quality-cost", "floor"):
            self.assertRegex(r.stdout, rf"(?m)^  {re.escape(name)} ", name)
        self.assertIn("passes", cli.CHART_NAMES)
        self.assertIn("results.json", r.stdout)
        self.assertEqual(cli.CHART_NAMES, SINGLE_FILE_CHARTS + ("history",))
        self.assertEqual(sorted(cli.SUBCOMMANDS), ["floor", "quality-cost"])
        for sub in cli.SUBCOMMANDS:
            r = run_charts(sub, "--help")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("--out DIR", r.stdout)

    def test_main_charts_from_committed_results(self):
        with tempfile.TemporaryDirectory() as tmp:
            r = run_charts(*SWEEPS, "--out", tmp)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = self.check_index(tmp, cli.CHART_NAMES)
            self.assertEqual([s["file"] for s in index["sources"]], SWEEPS)
            self.assertIn("NVIDIA H200", index["sources"][1]["device"])
            with open(os.path.join(tmp, "history.svg")) as f:
                svg = f.read()
            self.assertIn("2026-11-30_h200_full_sweep", svg)
            self.assertNotIn("full_sweep.json", svg)   # the file label drops .json.gz as it did .json

    def test_quality_cost_from_committed_results(self):
        bench = [os.path.join(QUALITY_COST, f"bench_{i}.json.gz") for i in range(3)]
        quality = [os.path.join(QUALITY_COST, q, "quality.json") for q in ("quality_full", "quality_half")]
        with tempfile.TemporaryDirectory() as tmp:
            r = run_charts("quality-cost", "--quality", *quality, "--bench", *bench, "--out", tmp)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(tmp, "quality_cost.json")) as f:
                points = json.load(f)["points"]
            self.assertGreater(len(points), 10)
            self.assertTrue(any(p["pareto"] for p in points))
            self.assertGreater(os.path.getsize(os.path.join(tmp, "quality_cost.png")), 1000)

    def test_floor_from_committed_results(self):
        with tempfile.TemporaryDirectory() as tmp:
            r = run_charts("floor", FLOOR_LIFT, "--filter", "/n16/b4/full/", "--out", tmp)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(tmp, "floor.svg")) as f:
                self.assertRegex(f.read(), r"\d\.\d\dx floor")
            self.assertGreater(os.path.getsize(os.path.join(tmp, "floor.png")), 1000)

    def test_synthetic_gzip_reads_as_plain(self):
        """A .json.gz, and gzip bytes under a .json name, give the charts of the plain file."""
        with tempfile.TemporaryDirectory() as tmp:
            with open(SAMPLE, "rb") as f:
                packed = gzip.compress(f.read(), mtime=0)
            gz, disguised = os.path.join(tmp, "sample.json.gz"), os.path.join(tmp, "gzip_bytes.json")
            for path in (gz, disguised):
                with open(path, "wb") as f:
                    f.write(packed)
            self.assertEqual(charts.load_results(gz)["records"], charts.load_results(SAMPLE)["records"])
            self.assertEqual(charts.load_results(disguised)["records"], charts.load_results(SAMPLE)["records"])
            r = run_charts(SAMPLE_OLD, gz, "--out", os.path.join(tmp, "out"))
            self.assertEqual(r.returncode, 0, r.stderr)
            self.check_index(os.path.join(tmp, "out"), cli.CHART_NAMES)
            # a name that is gone but whose .gz is there (a note written before compression) reads that
            self.assertEqual(cavity_json.resolve(gz[:-3]), gz)
            self.assertEqual(cavity_json.load(gz[:-3]), cavity_json.load(SAMPLE))

    def test_broken_gzip(self):
        with tempfile.TemporaryDirectory() as tmp:
            with open(SAMPLE, "rb") as f:
                packed = gzip.compress(f.read())
            bad = os.path.join(tmp, "cut.json.gz")
            with open(bad, "wb") as f:
                f.write(packed[: len(packed) // 2])
            out = os.path.join(tmp, "out")
            r = run_charts(SAMPLE, bad, "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(f"charts: {bad}: not a whole gzip file", r.stderr)
            self.assertFalse(os.path.exists(out))

    def test_table_scripts_read_gzip(self):
        r = subprocess.run([sys.executable, os.path.join(HERE, "floor_table.py"), os.path.join(FLOOR3, "fragment.json.gz")],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        self.assertIn("| measured / floor | registers |", r.stdout)
        self.assertGreater(len(r.stdout.splitlines()), 10)
        # The H200's register counts (testdata/2026-12-03_h200_shader_stats):
        # alchemy_fast's AO pass takes 31, as the driver reported there.
        stats = os.path.join(SHADER_STATS, "regs.json.gz")
        r = subprocess.run([sys.executable, os.path.join(HERE, "floor_table.py"), stats],
                           capture_output=True, text=True, timeout=120)
        self.assertEqual(r.returncode, 0, r.stderr)
        ao = [l for l in r.stdout.splitlines() if l.startswith("| corner/alchemy_fast/n16/b4/full/1920x1080/vk/compute | ao |")]
        self.assertEqual(len(ao), 1, r.stdout)
        self.assertTrue(ao[0].endswith("| 31 |"), ao[0])


def bench_doc(times, software=False, clock="gpu-timestamp", clocks=None):
    """cavity_bench JSON: {config id: [(pipeline ms, {pass: ms}) per repetition]}; clocks: {id: clock} overrides."""
    benchmarks = []
    for cid, reps in times.items():
        for i, (ms, passes) in enumerate(reps):
            e = {"name": cid + "/iterations:1/manual_time", "run_type": "iteration", "repetitions": len(reps),
                 "repetition_index": i, "real_time": ms, "time_unit": "ms",
                 "label": f"clock={(clocks or {}).get(cid, clock)} mode=drained"}
            e.update({f"pass_{p}_ms": v for p, v in passes.items()})
            benchmarks.append(e)
    dev = "llvmpipe (LLVM 15.0.6, 256 bits)" if software else "NVIDIA H200"
    return {"context": {"date": "2026-12-03T10:00:00+00:00", "cavity_device": f"gl: {dev}; vk: {dev}",
                        "cavity_software_renderer": "true" if software else "false"}, "benchmarks": benchmarks}


def results_doc(runs, software=True):
    """A results.json: {config id: (clock, {pass: [ms per frame]})}."""
    out = []
    for cid, (clock, passes) in runs.items():
        frames = len(next(iter(passes.values())))
        out.append({"id": cid, "backend": cid.split("/")[6], "clock": clock,
                    "device": {"name": "llvmpipe (LLVM 15.0.6, 256 bits)" if software else "NVIDIA H200",
                               "software_renderer": software, "driver": "Mesa 22.3.6"},
                    "frame": {"samples_ms": [sum(v[k] for v in passes.values()) for k in range(frames)]},
                    "passes": [{"name": n, "samples_ms": v} for n, v in passes.items()]})
    return {"schema": "cavity.results/1", "created_utc": "2026-12-03T10:00:00Z", "runs": out}


def write_json(d, name, doc):
    path = os.path.join(d, name)
    with open(path, "w") as f:
        json.dump(doc, f)
    return path


def index_of(out):
    with open(os.path.join(out, "index.json")) as f:
        return {c["name"]: c for c in json.load(f)["charts"]}


def quartiles(v):
    """The 25th and 75th percentiles, linear between order statistics, computed here independently."""
    v = sorted(v)
    def q(p):
        pos = (len(v) - 1) * p
        lo = int(pos)
        return v[lo] + (v[min(lo + 1, len(v) - 1)] - v[lo]) * (pos - lo)
    return q(0.25), q(0.75)


# A CPU-renderer sweep like the one that misled: one OpenGL repetition at n16 took over twice as
# long as the others, so its median and its spread are wide, and full/half and gl/vk drawn from it are noise.
NOISY = {
    "corner/alchemy/n4/b4/full/320x180/gl/compute": [52, 50, 55],
    "corner/alchemy/n16/b4/full/320x180/gl/compute": [60, 146, 95],
    "corner/alchemy/n64/b4/full/320x180/gl/compute": [62, 61, 64],
    "corner/alchemy/n16/b4/half/320x180/gl/compute": [22, 60, 30],
    "corner/alchemy/n4/b4/full/320x180/vk/compute": [50, 51, 52],
    "corner/alchemy/n16/b4/full/320x180/vk/compute": [58, 59, 61],
    "corner/alchemy/n64/b4/full/320x180/vk/compute": [63, 62, 66],
    "corner/alchemy/n16/b4/half/320x180/vk/compute": [20, 21, 22],
}


def noisy_doc(software=True, clock="wall", clocks=None):
    return bench_doc({cid: [(ms, {"ao": ms * 0.2, "blur": ms * 0.75, "composite": ms * 0.05, "gbuffer": 3.0})
                            for ms in reps] for cid, reps in NOISY.items()}, software, clock, clocks)


class Spread(unittest.TestCase):
    """Every timing chart draws the spread of each configuration's repetitions, and ratios carry theirs."""

    def test_whiskers_are_the_repetitions_quartiles(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            r = run_charts(write_json(d, "cpu.json", noisy_doc()), "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            points = {p["id"]: p for s in index["time_vs_samples"]["points"].values() for p in s}
            self.assertEqual(len(points), 6)
            for cid, p in points.items():
                q25, q75 = quartiles(NOISY[cid])
                self.assertAlmostEqual(p["ms"], sorted(NOISY[cid])[1])
                self.assertAlmostEqual(p["q25"], q25)
                self.assertAlmostEqual(p["q75"], q75)
                self.assertEqual(p["n"], 3)
            self.assertIn("interquartile range of each configuration's 3 repetitions",
                          index["time_vs_samples"]["spread"])

    def test_ratios_carry_their_range_and_overlap(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            r = run_charts(write_json(d, "cpu.json", noisy_doc()), "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            gl = index["full_vs_half"]["ratios"]["alchemy · OpenGL"]
            vk = index["full_vs_half"]["ratios"]["alchemy · Vulkan"]
            full, half = quartiles(NOISY["corner/alchemy/n16/b4/full/320x180/gl/compute"]), \
                quartiles(NOISY["corner/alchemy/n16/b4/half/320x180/gl/compute"])
            self.assertAlmostEqual(gl["low"], full[0] / half[1])
            self.assertAlmostEqual(gl["high"], full[1] / half[0])
            self.assertFalse(gl["overlap"])          # 60..146 against 22..60: still apart
            self.assertFalse(vk["overlap"])
            self.assertLess(vk["high"] - vk["low"], gl["high"] - gl["low"])
            pairs = {p["id"]: p for p in index["gl_vs_vk"]["pairs"]}
            n16 = pairs["corner/alchemy/n16/b4/full/320x180/*/compute"]
            self.assertAlmostEqual(n16["change_pct"], (59 / 95 - 1) * 100)
            self.assertFalse(n16["overlap"])
            n64 = pairs["corner/alchemy/n64/b4/full/320x180/*/compute"]
            self.assertTrue(n64["overlap"])          # 61..64 against 62..66: the difference is noise
            with open(os.path.join(out, "gl_vs_vk.svg")) as f:
                self.assertTrue("2 of 4 differ by less than their spreads (hollow)" in f.read())

    def test_one_repetition_says_so(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            one = bench_doc({cid: [(reps[0], {"ao": 1.0})] for cid, reps in NOISY.items()})
            self.assertEqual(run_charts(write_json(d, "one.json", one), "--out", out).returncode, 0)
            entry = index_of(out)["time_vs_samples"]
            self.assertIn("one sample per configuration: no spread to draw", entry["spread"])
            self.assertTrue(all(p["q25"] is None for s in entry["points"].values() for p in s))


def png_width(path):
    with open(path, "rb") as f:
        head = f.read(24)
    return int.from_bytes(head[16:20], "big")


class Crowded(unittest.TestCase):
    """A sweep of 12 kernels on both APIs: at most 8 series a chart, no chart
    wider than 2,000 px, and --filter picks which configurations are drawn."""

    KERNELS = [f"k{i:02d}" for i in range(12)]

    def doc(self):
        times = {}
        for i, k in enumerate(self.KERNELS):
            for api in ("vk", "gl"):
                for n in (8, 16, 32):
                    for res in ("full", "half"):
                        ms = (0.1 + 0.01 * i) * n / 16 * (0.4 if res == "half" else 1)
                        times[f"corner/{k}/n{n}/b4/{res}/1920x1080/{api}/compute"] = [
                            (ms * (1 + 0.01 * r), {"ao": ms * 0.8}) for r in range(5)]
        return bench_doc(times)

    def test_at_most_eight_series_and_2000_px(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = write_json(tmp, "bench.json", self.doc())
            out = os.path.join(tmp, "charts")
            r = run_charts(path, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            self.assertEqual(len(index["time_vs_samples"]["points"]), 8)
            self.assertEqual(len(index["full_vs_half"]["labels"]), 8)
            self.assertEqual(len({p["id"].split("/")[1] for p in index["gl_vs_vk"]["pairs"]}), 8)
            # every kernel of the sweep its own colour
            self.assertEqual(len(set(charts.kernel_colours(self.KERNELS).values())), len(self.KERNELS))
            with open(os.path.join(out, "time_vs_samples.svg")) as f:
                self.assertTrue("the first 8 of 24 series" in f.read(), "the subtitle says what was left out")
            for c in index.values():
                self.assertLessEqual(png_width(os.path.join(out, c["png"])), 2000, c["name"])

    def test_filter_picks_the_configurations(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = write_json(tmp, "bench.json", self.doc())
            out = os.path.join(tmp, "charts")
            r = run_charts(path, "--out", out, "--filter", "/k0[0-2]/")
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            self.assertEqual(sorted(index["time_vs_samples"]["points"]),
                             sorted(f"k0{i} · {api}" for i in range(3) for api in ("Vulkan", "OpenGL")))
            with open(os.path.join(out, "time_vs_samples.svg")) as f:
                self.assertFalse("series (--filter" in f.read(), "nothing left out")
            for bad, says in (("/nothing/", "matches no configuration"), ("(", "not a regular expression")):
                r = run_charts(path, "--out", os.path.join(tmp, "x"), "--filter", bad)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
                self.assertIn(says, r.stderr)
                self.assertFalse(os.path.exists(os.path.join(tmp, "x")))


class Clock(unittest.TestCase):
    """The time axis and subtitle name the clock: GPU timestamps, a CPU renderer's wall clock, or mixed."""

    def clock_of(self, doc, name="time_vs_samples"):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            r = run_charts(write_json(d, "b.json", doc), "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            with open(os.path.join(out, name + ".svg")) as f:
                return index[name], f.read()

    def test_gpu(self):
        entry, svg = self.clock_of(noisy_doc(software=False, clock="gpu-timestamp"))
        self.assertEqual(entry["clock"], "clock: GPU timestamps")
        self.assertTrue(entry["axis"][0].endswith("GPU timestamps"), entry["axis"])
        self.assertIn("GPU timestamps", svg)
        self.assertNotIn("CPU renderer", svg)

    def test_cpu_renderer(self):
        entry, svg = self.clock_of(noisy_doc(software=True, clock="wall"))
        self.assertEqual(entry["clock"], "clock: wall clock, CPU renderer")
        self.assertTrue(entry["axis"][0].endswith("wall clock, CPU renderer"), entry["axis"])
        self.assertNotIn("GPU time", svg)
        self.assertNotIn("GPU timestamps", svg)

    def test_mixed(self):
        entry, _ = self.clock_of(noisy_doc(clocks={"corner/alchemy/n4/b4/full/320x180/vk/compute": "gpu-timestamp"}))
        self.assertIn("MIXED CLOCKS in this chart: 5 on wall clock, CPU renderer, 1 on timestamps, CPU renderer",
                      entry["clock"])
        self.assertIn("mixed clocks", entry["axis"][0])


RESULTS_RUNS = {
    f"corner/alchemy/n{n}/b4/{res}/160x90/{api}/compute": (
        "wall", {"gbuffer": [1.0, 1.1, 1.0, 1.2], "ao": [n * 0.1 * k for k in (1.0, 1.1, 0.9, 1.3)],
                 "blur": [5.0, 5.5, 4.5, 6.0], "composite": [0.2, 0.2, 0.3, 0.2]})
    for n in (4, 16, 64) for res in ("full", "half") for api in ("gl", "vk")}


class ResultsJson(unittest.TestCase):
    """cavity run's results.json charts like cavity_bench JSON: frames are the samples, the AO pipeline
    of a frame its passes but the G-buffer."""

    def test_main_charts(self):
        with tempfile.TemporaryDirectory() as d:
            path = write_json(d, "results.json", results_doc(RESULTS_RUNS))
            out = os.path.join(d, "out")
            r = run_charts(path, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            index = index_of(out)
            self.assertEqual(sorted(index), sorted(["time_vs_samples", "full_vs_half", "gl_vs_vk", "passes"]))
            cid = "corner/alchemy/n16/b4/full/160x90/vk/compute"
            passes = RESULTS_RUNS[cid][1]
            frames = [passes["ao"][k] + passes["blur"][k] + passes["composite"][k] for k in range(4)]
            point = next(p for s in index["time_vs_samples"]["points"].values() for p in s if p["id"] == cid)
            self.assertAlmostEqual(point["ms"], (sorted(frames)[1] + sorted(frames)[2]) / 2)
            self.assertAlmostEqual(point["q25"], quartiles(frames)[0])
            self.assertEqual(point["n"], 4)
            self.assertIn("4 frames", index["time_vs_samples"]["spread"])
            self.assertEqual(index["time_vs_samples"]["clock"], "clock: wall clock, CPU renderer")

    def test_bad_results_json(self):
        runs = dict(RESULTS_RUNS)
        doc = results_doc(runs)
        doc["runs"][3]["clock"] = "sundial"
        with tempfile.TemporaryDirectory() as d:
            path = write_json(d, "results.json", doc)
            out = os.path.join(d, "out")
            r = run_charts(SAMPLE, path, "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(f"charts: {path}: runs[3] '{doc['runs'][3]['id']}': clock 'sundial' (gpu-timestamp or wall)",
                          r.stderr)
            self.assertEqual(r.stdout, "")
            self.assertFalse(os.path.exists(out))


    def test_title_that_cannot_be_drawn(self):
        # 5,000 characters overflowed matplotlib's glyph raster: a traceback.
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            for title, words in (("x" * 5000, "--title: 5000 characters"), ("a\nb", "with a line break")):
                r = run_charts(SAMPLE, "--out", out, "--title", title)
                self.assertEqual(r.returncode, 2, r.stderr)
                self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
                self.assertIn(words, r.stderr)
                self.assertFalse(os.path.exists(out))


class Passes(unittest.TestCase):
    """The passes chart: each pass's median and spread per kernel and API, from both formats, G-buffer left out."""

    def test_from_benchmark_json(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            self.assertEqual(run_charts(write_json(d, "b.json", noisy_doc()), "--out", out).returncode, 0)
            entry = index_of(out)["passes"]
            rows = {row["id"]: row for row in entry["rows"]}
            cid = "corner/alchemy/n16/b4/full/320x180/gl/compute"
            self.assertIn(cid, rows)
            self.assertEqual(entry["left_out"], ["gbuffer"])
            self.assertEqual(entry["pass_order"], ["ao", "blur", "composite"])
            ao = [ms * 0.2 for ms in NOISY[cid]]
            self.assertAlmostEqual(rows[cid]["passes"]["ao"]["ms"], sorted(ao)[1])
            self.assertAlmostEqual(rows[cid]["passes"]["ao"]["q75"], quartiles(ao)[1])
            self.assertEqual(len(rows), 2)   # the slice: alchemy on both APIs at n16, full

    def test_from_results_json(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "out")
            self.assertEqual(run_charts(write_json(d, "r.json", results_doc(RESULTS_RUNS)), "--out", out).returncode, 0)
            entry = index_of(out)["passes"]
            self.assertEqual(entry["left_out"], ["gbuffer"])
            for row in entry["rows"]:
                raw = RESULTS_RUNS[row["id"]][1]
                for name, st in row["passes"].items():
                    self.assertAlmostEqual(st["q25"], quartiles(raw[name])[0])
                    self.assertEqual(st["n"], 4)

    def test_committed_sweep_with_repetitions(self):
        with tempfile.TemporaryDirectory() as d:
            r = run_charts(os.path.join(FLOOR3, "compute.json.gz"), "--out", d)
            self.assertEqual(r.returncode, 0, r.stderr)
            entry = index_of(d)["passes"]
            kernels = {row["id"].split("/")[1] for row in entry["rows"]}
            self.assertTrue({"alchemy_fast", "hemisphere_fast", "ssdo_fast"} <= kernels, kernels)
            self.assertTrue(all(row["n"] == 10 for row in entry["rows"]))
            self.assertEqual(entry["clock"], "clock: GPU timestamps")


class QualityCost(unittest.TestCase):
    """The quality-cost subcommand: quality.json rows joined with the AO
    passes' time of the same configuration, and the Pareto front."""

    def test_pareto_front(self):
        # (cost, error): (2, 0.5) is beaten by (1, 0.4); (3, 0.1) and (1, 0.4) are not beaten.
        pts = [(2.0, 0.5), (1.0, 0.4), (3.0, 0.1), (4.0, 0.1), (0.5, 0.9)]
        self.assertEqual(charts.pareto_front(pts), [4, 1, 2])

    def write_inputs(self, d):
        def quality(res, maes):
            rows = [{"scene": sc, "kernel": k, "samples": n, "mae": m, "max_abs": 1, "mean_ao": 0.9,
                     "mean_truth": 0.9, "pixels": 10} for (sc, k, n), m in maes.items()]
            doc = {"schema": "cavity.quality/1", "backend": "vk", "device": "Test GPU", "width": 1920, "height": 1080,
                   "rays": 1024, "resolution": res, "reach": "shared", "radius": 0.5, "rows": rows}
            path = os.path.join(d, f"quality_{res}.json")
            with open(path, "w") as f:
                json.dump(doc, f)
            return path

        full = quality("full", {("corner", "alchemy", 16): 0.04, ("slats", "alchemy", 16): 0.10,
                                ("corner", "hemisphere", 16): 0.30, ("slats", "hemisphere", 16): 0.30,
                                ("corner", "ssdo", 16): 0.05, ("slats", "ssdo", 16): 0.05})
        half = quality("half", {("corner", "alchemy", 16): 0.06, ("slats", "alchemy", 16): 0.12,
                                ("corner", "nobench", 16): 0.01})
        bench = []
        for cid, ao, box in (("corner/alchemy/n16/b4/full/1920x1080/vk/compute", 0.20, None),
                             ("corner/hemisphere/n16/b4/full/1920x1080/vk/compute", 0.10, 0.02),
                             ("corner/ssdo/n16/b4/full/1920x1080/vk/compute", 0.50, None),
                             ("corner/alchemy/n16/b4/half/1920x1080/vk/compute", 0.05, None)):
            for rep in (0.9, 1.0, 1.2):   # three repetitions: the median is the middle one
                e = {"name": cid + "/manual_time", "run_type": "iteration", "real_time": 1.0, "time_unit": "ms",
                     "pass_ao_ms": ao * rep}
                if box is not None:
                    e["pass_box_ms"] = box
                bench.append(e)
            bench.append({"name": cid + "@ao", "run_type": "iteration", "real_time": 9.0, "time_unit": "ms"})
        bpath = os.path.join(d, "bench.json")
        with open(bpath, "w") as f:
            json.dump({"context": {"date": "2026-12-01"}, "benchmarks": bench}, f)
        return full, half, bpath

    def test_joined_points_and_front(self):
        with tempfile.TemporaryDirectory() as d:
            full, half, bench = self.write_inputs(d)
            out = os.path.join(d, "out")
            r = run_charts("quality-cost", "--quality", full, half, "--bench", bench, "--out", out, "--cost", "estimate")
            self.assertEqual(r.returncode, 0, r.stderr)
            self.assertIn("corner/nobench/n16/b4/half/1920x1080/vk/compute", r.stderr)
            for name in ("quality_cost.png", "quality_cost.svg", "quality_cost.json"):
                self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
            with open(os.path.join(out, "quality_cost.json")) as f:
                doc = json.load(f)
            pts = {(p["kernel"], p["res"]): p for p in doc["points"]}
            self.assertEqual(len(pts), 4)
            self.assertAlmostEqual(pts[("alchemy", "full")]["mae"], 0.07)      # mean over the two scenes
            self.assertAlmostEqual(pts[("alchemy", "full")]["ms"], 0.20)       # median of 0.18, 0.20, 0.24
            self.assertAlmostEqual(pts[("hemisphere", "full")]["ms"], 0.12)    # ao + box
            # Half and full alchemy are on the front (each the cheapest at its error); the hemisphere
            # is beaten by half alchemy (cheaper and more exact); ssdo, the most exact, is on it too.
            self.assertEqual({k for k, p in pts.items() if p["pareto"]},
                             {("alchemy", "half"), ("alchemy", "full"), ("ssdo", "full")})

    def test_front_is_screen_space_with_fast_kernels(self):
        """An SDF kernel cheaper and closer to the truth than everything stays off the front (an engine
        cannot run it on its G-buffer), as `cavity quality --cost` leaves it off; the _fast kernels are
        points like any other. The cost is the whole pipeline (real_time), as cavity quality's."""
        with tempfile.TemporaryDirectory() as d:
            maes = {"alchemy": 0.07, "alchemy_fast": 0.07, "hemisphere_fast": 0.045, "ssdo_fast": 0.06,
                    "sdf_multiplicative": 0.03}
            rows = [{"scene": sc, "kernel": k, "samples": 16, "mae": m, "max_abs": 1, "mean_ao": 0.9,
                     "mean_truth": 0.9, "pixels": 10} for k, m in maes.items() for sc in ("corner", "slats")]
            q = write_json(d, "q.json", {"schema": "cavity.quality/1", "backend": "vk", "device": "Test GPU",
                                         "width": 1920, "height": 1080, "rays": 1024, "resolution": "full",
                                         "reach": "shared", "radius": 0.5, "blur": 4, "rows": rows})
            pipeline = {"alchemy": 0.86, "alchemy_fast": 0.30, "hemisphere_fast": 0.43, "ssdo_fast": 2.27,
                        "sdf_multiplicative": 0.25}
            doc = bench_doc({f"corner/{k}/n16/b4/full/1920x1080/vk/compute":
                             [(ms * f, {"ao": ms * 0.4 * f, "blur": ms * 0.5, "gbuffer": 0.08}) for f in (0.98, 1.0, 1.03)]
                             for k, ms in pipeline.items()})
            b = write_json(d, "bench.json", doc)
            out = os.path.join(d, "out")
            r = run_charts("quality-cost", "--quality", q, "--bench", b, "--out", out)
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(out, "quality_cost.json")) as f:
                result = json.load(f)
            pts = {p["kernel"]: p for p in result["points"]}
            self.assertEqual(set(pts), set(maes))
            self.assertFalse(pts["sdf_multiplicative"]["screen_space"])
            self.assertFalse(pts["sdf_multiplicative"]["pareto"])
            self.assertEqual({k for k, p in pts.items() if p["pareto"]}, {"alchemy_fast", "hemisphere_fast"})
            self.assertAlmostEqual(pts["hemisphere_fast"]["ms"], 0.43)
            self.assertAlmostEqual(pts["hemisphere_fast"]["q75"], 0.43 * 1.015)
            self.assertEqual(result["front"][0], "corner/alchemy_fast/n16/b4/full/1920x1080/vk/compute")
            self.assertEqual(result["cost"], "pipeline")

    def test_committed_results_front_and_labels(self):
        """On the committed H200 data: no SDF kernel on the front, every fast kernel the data has is drawn,
        and no two labels overlap."""
        floor3 = FLOOR3
        sets = {"sdf": (["quality_full/quality.json", "quality_half/quality.json"], QUALITY_COST,
                        [f"bench_{i}.json.gz" for i in range(3)]),
                "fast": (["quality_corner_b4/quality.json", "quality_slats_b4/quality.json"], floor3,
                         ["compute.json.gz"])}
        for name, (quality, folder, bench) in sets.items():
            with tempfile.TemporaryDirectory() as d:
                r = run_charts("quality-cost", "--quality", *[os.path.join(folder, q) for q in quality],
                               "--bench", *[os.path.join(folder, b) for b in bench], "--out", d)
                self.assertEqual(r.returncode, 0, r.stderr)
                with open(os.path.join(d, "quality_cost.json")) as f:
                    result = json.load(f)
                front = [p for p in result["points"] if p["pareto"]]
                self.assertTrue(front, name)
                self.assertTrue(all(not p["kernel"].startswith("sdf_") for p in front), name)
                kernels = {p["kernel"] for p in result["points"]}
                if name == "sdf":
                    self.assertTrue(any(k.startswith("sdf_") for k in kernels))
                else:
                    self.assertTrue({"alchemy_fast", "hemisphere_fast", "ssdo_fast"} <= kernels, kernels)
                    self.assertIn("corner/hemisphere_fast/n16/b4/full/1920x1080/vk/compute", result["front"])
                boxes = [l["box"] for l in result["labels"]]
                self.assertGreaterEqual(len(boxes), len(front))
                for i, a in enumerate(boxes):
                    for b in boxes[i + 1:]:
                        apart = a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1]
                        self.assertTrue(apart, (name, a, b))

    def test_quality_files_must_agree(self):
        with tempfile.TemporaryDirectory() as d:
            full, half, bench = self.write_inputs(d)
            with open(half) as f:
                doc = json.load(f)
            doc["blur"] = 4
            with open(half, "w") as f:
                json.dump(doc, f)
            r = run_charts("quality-cost", "--quality", full, half, "--bench", bench, "--out", os.path.join(d, "o"))
            self.assertEqual(r.returncode, 2)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)
            self.assertIn(f"the --quality files differ in blur ({full}: None, {half}: 4)", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "o")))

    def test_bad_input(self):
        with tempfile.TemporaryDirectory() as d:
            full, half, bench = self.write_inputs(d)
            r = run_charts("quality-cost", "--quality", bench, "--bench", bench, "--out", os.path.join(d, "o"))
            self.assertEqual(r.returncode, 2)
            self.assertIn("not a cavity quality.json", r.stderr)
            self.assertFalse(os.path.exists(os.path.join(d, "o")))
            r = run_charts("quality-cost", "--quality", full, "--bench", full, "--out", os.path.join(d, "o"))
            self.assertEqual(r.returncode, 2)
            self.assertEqual(len(r.stderr.strip().splitlines()), 1)


class Floor(unittest.TestCase):
    """The floor subcommand: measured against floor per pass from results.json, null floors included."""

    @staticmethod
    def write_results(d, floors):
        def pass_(name, ms, floor, reason):
            return {"name": name, "kernel": name, "width": 1920, "height": 1080, "shader_path": "spirv", "shader_stats": [], "shader_stats_reason": "",
                    "stats": {"count": 1, "median_ms": ms, "min_ms": ms, "max_ms": ms, "mean_ms": ms, "p90_ms": ms,
                              "stddev_ms": 0, "cv": 0}, "samples_ms": [ms],
                    "floor": None if floor is None else {"floor_ms": floor, "bound": "fetch"}, "floor_reason": reason}
        passes = [pass_("ao", 0.2, 0.1388 if floors else None, "" if floors else "software renderer (x): no GPU floor"),
                  pass_("gbuffer", 0.05, None, "no cost declared")]
        doc = {"schema": "cavity.results/1", "runs": [{"id": "corner/alchemy/n16/b4/full/1920x1080/vk/compute",
                                                        "device": {"name": "NVIDIA H200"}, "passes": passes}]}
        path = os.path.join(d, "results.json")
        with open(path, "w") as f:
            json.dump(doc, f)
        return path

    def test_rows(self):
        with tempfile.TemporaryDirectory() as d:
            rows = charts.load_floor_rows(self.write_results(d, True))
        self.assertEqual([(r["pass"], r["ms"], r["floor"], r["reason"]) for r in rows],
                         [("ao", 0.2, 0.1388, ""), ("gbuffer", 0.05, None, "no cost declared")])

    def test_chart_with_and_without_floors(self):
        for floors in (True, False):
            with tempfile.TemporaryDirectory() as d:
                out = os.path.join(d, "out")
                r = run_charts("floor", self.write_results(d, floors), "--out", out)
                self.assertEqual(r.returncode, 0, r.stderr)
                for name in ("floor.png", "floor.svg"):
                    self.assertTrue(os.path.getsize(os.path.join(out, name)) > 0, name)
                with open(os.path.join(out, "floor.svg")) as f:
                    svg = f.read()
                if floors:
                    self.assertEqual(r.stderr, "")
                    self.assertIn("1.44x floor", svg)   # 0.2 / 0.1388
                else:
                    self.assertIn("no pass has a floor (no cost declared; software renderer (x): no GPU floor)", r.stderr)

    def test_benchmark_json(self):
        """cavity_bench's per-pass entries: the median aggregate is the measurement, and the floor
        comes from the repetitions, never from an aggregate (whose floor_ms is a stddev or a cv)."""
        cid = "corner/alchemy_fast/n16/b4/full/1920x1080/vk/compute"
        def entry(kind, ms, floor, agg=None):
            e = {"name": f"{cid}@ao/iterations:1/manual_time", "run_name": f"{cid}@ao/iterations:1/manual_time",
                 "run_type": kind, "real_time": ms, "time_unit": "ms", "floor_ms": floor}
            if agg:
                e["aggregate_name"] = agg
            return e
        doc = {"context": {"cavity_device": "vk: NVIDIA H200"},
               "benchmarks": [entry("iteration", 0.14, 0.0377), entry("iteration", 0.15, 0.0377),
                              entry("iteration", 0.13, 0.0377), entry("aggregate", 0.142, 0.0377, "median"),
                              entry("aggregate", 0.01, 0.0, "stddev"), entry("aggregate", 0.0, 0.0, "cv"),
                              {"name": cid + "/iterations:1/manual_time", "run_type": "iteration", "real_time": 0.3}]}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bench.json")
            with open(path, "w") as f:
                json.dump(doc, f)
            rows = charts.load_floor_rows(path)
            self.assertEqual([(r["id"], r["pass"], r["ms"], r["floor"]) for r in rows], [(cid, "ao", 0.142, 0.0377)])
            r = run_charts("floor", path, "--filter", "alchemy_fast", "--out", os.path.join(d, "out"))
            self.assertEqual(r.returncode, 0, r.stderr)
            with open(os.path.join(d, "out", "floor.svg")) as f:
                self.assertIn("3.77x floor", f.read())   # 0.142 / 0.0377
            r = run_charts("floor", path, "--filter", "hemisphere", "--out", os.path.join(d, "none"))
            self.assertEqual(r.returncode, 2)
            self.assertIn("matches no configuration", r.stderr)

    def test_bad_input(self):
        with tempfile.TemporaryDirectory() as d:
            out = os.path.join(d, "o")
            r = run_charts("floor", SAMPLE, "--out", out)   # benchmark JSON without per-pass entries
            self.assertEqual(r.returncode, 2)
            self.assertIn("no <id>@<pass> entries", r.stderr)
            self.assertFalse(os.path.exists(out))
            other = os.path.join(d, "other.json")
            with open(other, "w") as f:
                json.dump({"schema": "something/1"}, f)
            r = run_charts("floor", other, "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertIn("neither a cavity results.json", r.stderr)
            r = run_charts("floor", self.write_results(d, True), "--filter", "(", "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertIn("--filter '(': not a regular expression", r.stderr)
            self.assertFalse(os.path.exists(out))
            path = self.write_results(d, True)
            with open(path) as f:
                doc = json.load(f)
            del doc["runs"][0]["passes"][0]["floor"]   # a results.json from before floors
            with open(path, "w") as f:
                json.dump(doc, f)
            r = run_charts("floor", path, "--out", out)
            self.assertEqual(r.returncode, 2)
            self.assertIn("lacks a field the chart needs", r.stderr)
            self.assertFalse(os.path.exists(out))


class FloorTable(unittest.TestCase):
    """floor_table.py: each pass's median against its floor, and the pipeline's: the median of
    the repetitions' sums (the G-buffer not counted) against the sum of the floors."""

    def test_pipeline_row(self):
        def rep(cid, ao, blur, floors=True):
            b = {"name": cid + "/iterations:1/manual_time", "run_type": "iteration", "real_time": ao + blur,
                 "pass_gbuffer_ms": 0.09, "pass_ao_ms": ao, "pass_blur_ms": blur, "sm_mhz_median": 1980}
            if floors:
                b.update({"floor_ao_ms": 0.07, "floor_blur_ms": 0.01})
            else:
                b["floor_ao_ms"] = 0.07   # the blur has none (a software renderer has neither)
            return b
        a, c = "corner/alchemy_fast/n16/b4/full/1920x1080/vk/compute", "corner/alchemy_fast/n16/b4/full/1920x1080/gl/compute"
        # Sums 0.10, 0.12 and 0.14: the median 0.12, where the passes' medians (0.09 + 0.03) sum alike.
        doc = {"benchmarks": [rep(a, 0.08, 0.02), rep(a, 0.09, 0.03), rep(a, 0.10, 0.04), rep(c, 0.1, 0.03, floors=False)]}
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "bench.json")
            with open(path, "w") as f:
                json.dump(doc, f)
            r = subprocess.run([sys.executable, os.path.join(HERE, "floor_table.py"), path],
                               capture_output=True, text=True)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = {tuple(c.strip() for c in line.strip("|").split("|")[:2]): [c.strip() for c in line.strip("|").split("|")[2:]]
                for line in r.stdout.splitlines() if line.startswith("| corner/")}
        pipeline = "pipeline (2 passes, the G-buffer not counted)"
        self.assertEqual(rows[(a, pipeline)][:3], ["0.1200", "0.0800", "1.50x"])
        self.assertEqual(rows[(a, "ao")][:3], ["0.0900", "0.0700", "1.29x"])
        self.assertEqual(rows[(c, pipeline)][:3], ["0.1300", "-", "-"])   # a pass without a floor: no sum


if __name__ == "__main__":
    unittest.main()
