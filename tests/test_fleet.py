#!/usr/bin/env python3
"""The gate spread over GPUs and machines.

    test_fleet.py TEST CAVITY SOURCE_DIR BUILD_DIR

TEST is one of ctest_resources, shard_protocols, flaky, expectations,
bisect (one CTest test each, tests/CMakeLists.txt). They run on the
software renderers with a few configurations of the `ci` matrix."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

CAVITY = SOURCE = BUILD = ""
# Four configurations: alchemy on corner, full and half, both APIs.
FILTER = r"^corner/alchemy/n16/b4/(full|half)/160x90/(gl|vk)/compute$"
TWO = r"^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$"
VK = "corner/alchemy/n16/b4/full/160x90/vk/compute"
GL = "corner/alchemy/n16/b4/full/160x90/gl/compute"
CLEAN_ENV = {k: v for k, v in os.environ.items()
             if k not in ("GTEST_SHARD_INDEX", "GTEST_TOTAL_SHARDS", "TEST_SHARD_INDEX", "TEST_TOTAL_SHARDS",
                          "GTEST_SHARD_STATUS_FILE", "TEST_SHARD_STATUS_FILE", "CAVITY_TEST_FLAKY")}


def run(args, env=None, cwd=None):
    e = dict(CLEAN_ENV, **(env or {}))
    return subprocess.run(args, capture_output=True, text=True, env=e, cwd=cwd or SOURCE)


def gate(*args, env=None):
    return run([CAVITY, "gate", "--matrix", "ci", *args], env=env)


def load(path):
    with open(path) as f:
        return json.load(f)


def verdicts(gate_json):
    return {r["id"]: (r["verdict"], r["passed"], tuple(i["digest"] for i in r["images"]))
            for r in load(gate_json)["results"]}


def report_data(html):
    """The data the gate inlined in its index.html (harness/report/)."""
    with open(html) as f:
        m = re.search(r'<script type="application/json" id="gate-data">(.*?)</script>', f.read(), re.S)
    return json.loads(m.group(1))


def rendered_dom(test, html):
    """The report's document once its script has run, as headless Chromium
    serialises it; without chromium a skip, or a failure under CI=true."""
    if not shutil.which("chromium"):
        if os.environ.get("CI") == "true":
            test.fail("chromium is not installed (scripts/setup.sh installs it)")
        test.skipTest("chromium is not installed")
    p = subprocess.run(["timeout", "120", "chromium", "--headless=new", "--no-sandbox", "--disable-gpu",
                        "--dump-dom", "file://" + os.path.abspath(html)],
                       capture_output=True, text=True)
    test.assertEqual(p.returncode, 0, p.stderr)
    return p.stdout


def one_line_error(test, p, *words):
    test.assertEqual(p.returncode, 2, p.stdout + p.stderr)
    lines = p.stderr.strip().splitlines()
    test.assertEqual(len(lines), 1, p.stderr)
    for w in words:
        test.assertIn(w, lines[0])


class Base(unittest.TestCase):
    def setUp(self):
        self._tmp = tempfile.TemporaryDirectory(prefix="cavity-fleet-")
        self.tmp = self._tmp.name

    def tearDown(self):
        self._tmp.cleanup()


class CtestResources(Base):
    def test_spec_from_devices(self):
        spec = os.path.join(self.tmp, "detected.json")
        p = run([sys.executable, "scripts/ctest_resources.py", "--out", spec])
        self.assertEqual(p.returncode, 0, p.stderr)
        gpus = load(spec)["local"][0]["gpus"]
        self.assertGreaterEqual(len(gpus), 1)
        for g in gpus:
            self.assertRegex(g["id"], r"^[0-9]+$")
            self.assertEqual(g["slots"], 1)
        two = os.path.join(self.tmp, "two.json")
        p = run([sys.executable, "scripts/ctest_resources.py", "--devices", "0", "--per-device", "2", "--out", two])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(load(two), {"version": {"major": 1, "minor": 0},
                                     "local": [{"gpus": [{"id": "0_0", "slots": 1}, {"id": "0_1", "slots": 1}]}]})
        p = run([sys.executable, "scripts/ctest_resources.py", "--per-device", "0", "--out", two])
        one_line_error(self, p, "--per-device 0", "1..64")
        p = run([sys.executable, "scripts/ctest_resources.py", "--devices", "a,1", "--out", two])
        one_line_error(self, p, "--devices a,1")

    def test_bad_resource_group_is_refused(self):
        p = run(["scripts/ctest_gate_shard.sh", "shard", CAVITY, "0", "2", "ci", "baselines", self.tmp, TWO],
                env={"CTEST_RESOURCE_GROUP_COUNT": "1", "CTEST_RESOURCE_GROUP_0": "gpus",
                     "CTEST_RESOURCE_GROUP_0_GPUS": "id:gpu0,slots:1"})
        one_line_error(self, p, "id:gpu0,slots:1", "id:K,slots:M")
        p = run(["scripts/ctest_gate_shard.sh", "shard", CAVITY, "0", "2", "ci", "baselines", self.tmp, TWO],
                env={"CTEST_RESOURCE_GROUP_COUNT": "2"})
        one_line_error(self, p, "CTEST_RESOURCE_GROUP_COUNT=2", "one group")

    def test_inner_ctest_over_two_gpus_equals_the_unsharded_gate(self):
        spec = os.path.join(self.tmp, "two.json")
        p = run([sys.executable, "scripts/ctest_resources.py", "--devices", "0", "--per-device", "2", "--out", spec])
        self.assertEqual(p.returncode, 0, p.stderr)
        shards = os.path.join(self.tmp, "shards")
        # The inner ctest runs in build/tests so that its Testing/ log is not the outer one's.
        p = run(["ctest", "--test-dir", os.path.join(BUILD, "tests"), "-L", "^gate$", "-j", "2",
                 "--resource-spec-file", spec, "--output-on-failure"],
                env={"CAVITY_GATE_OUT": shards, "CAVITY_GATE_FILTER": FILTER})
        print(p.stdout)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn("100% tests passed, 0 tests failed out of 3", p.stdout)
        self.assertRegex(p.stdout, r"gate_merge .*Passed")
        ids = set()
        for k in range(2):
            with open(os.path.join(shards, str(k), "resource.txt")) as f:
                self.assertIn(f.read().strip(), ("id:0_0,slots:1", "id:0_1,slots:1"), "no GPU from the spec")
            g = load(os.path.join(shards, str(k), "gate.json"))
            self.assertEqual(g["shard"], [k, 2])
            mine = {r["id"] for r in g["results"]}
            self.assertTrue(mine)
            self.assertFalse(mine & ids, "shards overlap")
            ids |= mine
        whole = os.path.join(self.tmp, "whole")
        p = gate("--filter", FILTER, "--out", whole)
        self.assertEqual(p.returncode, 0, p.stderr)
        merged = load(os.path.join(shards, "merged", "gate.json"))
        self.assertEqual(merged["exit_code"], load(os.path.join(whole, "gate.json"))["exit_code"])
        self.assertEqual(verdicts(os.path.join(shards, "merged", "gate.json")), verdicts(os.path.join(whole, "gate.json")))
        self.assertEqual(ids, set(verdicts(os.path.join(whole, "gate.json"))))
        self.assertEqual(len(ids), 4)


    def test_inner_ctest_spreads_the_bench_sweep(self):
        spec = os.path.join(self.tmp, "two.json")
        p = run([sys.executable, "scripts/ctest_resources.py", "--devices", "0", "--per-device", "2", "--out", spec])
        self.assertEqual(p.returncode, 0, p.stderr)
        shards = os.path.join(self.tmp, "bench")
        wanted = r"^corner/alchemy/n(4|16|64)/b4/full/320x180/gl/compute/"
        p = run(["ctest", "--test-dir", os.path.join(BUILD, "tests"), "-L", "^bench$", "-j", "2",
                 "--resource-spec-file", spec, "--output-on-failure"],
                env={"CAVITY_GATE_OUT": shards, "CAVITY_BENCH_FILTER": wanted})
        print(p.stdout)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn("100% tests passed, 0 tests failed out of 3", p.stdout)
        names = []
        for k in range(2):
            part = [b["name"] for b in load(os.path.join(shards, f"bench-{k}.json"))["benchmarks"] if "@" not in b["name"]]
            self.assertTrue(part, f"bench shard {k} ran nothing")
            names += part
        self.assertEqual(len(names), len(set(names)), "bench shards overlap")
        merged = [b["name"] for b in load(os.path.join(shards, "bench.json"))["benchmarks"] if "@" not in b["name"]]
        self.assertEqual(sorted(merged), sorted(names))
        self.assertEqual(sorted(n.split("/")[2] for n in merged), ["n16", "n4", "n64"])


class ShardProtocols(Base):
    def listing(self, args=(), env=None):
        p = gate("--list", *args, env=env)
        self.assertEqual(p.returncode, 0, p.stderr)
        return p.stdout.split()

    def test_every_protocol_gives_the_same_disjoint_cover(self):
        everything = self.listing()
        # The whole ci matrix, each id once (80 configurations when written;
        # the partitions below are checked against this list itself).
        self.assertGreaterEqual(len(everything), 70)
        self.assertEqual(len(everything), len(set(everything)))
        n = 3
        partitions = {}
        for name in ("flag", "gtest", "bazel", "both"):
            shards = []
            for i in range(n):
                status = os.path.join(self.tmp, f"{name}{i}.status")
                env, args = {}, ()
                if name == "flag":
                    args = ("--shard", f"{i}/{n}")
                if name in ("gtest", "both"):
                    env.update(GTEST_SHARD_INDEX=str(i), GTEST_TOTAL_SHARDS=str(n), GTEST_SHARD_STATUS_FILE=status)
                if name in ("bazel", "both"):
                    env.update(TEST_SHARD_INDEX=str(i), TEST_TOTAL_SHARDS=str(n), TEST_SHARD_STATUS_FILE=status + ".bazel")
                shards.append(self.listing(args, env))
                if name in ("gtest", "both"):
                    self.assertTrue(os.path.exists(status), "GTEST_SHARD_STATUS_FILE not touched")
                if name in ("bazel", "both"):
                    self.assertTrue(os.path.exists(status + ".bazel"), "TEST_SHARD_STATUS_FILE not touched")
            flat = [x for s in shards for x in s]
            self.assertEqual(len(flat), len(set(flat)), f"{name}: shards overlap")
            self.assertEqual(sorted(flat), sorted(everything), f"{name}: shards do not cover the matrix")
            self.assertTrue(all(shards), f"{name}: an empty shard")
            partitions[name] = shards
        self.assertEqual(partitions["flag"], partitions["gtest"])
        self.assertEqual(partitions["flag"], partitions["bazel"])
        self.assertEqual(partitions["flag"], partitions["both"])

    def test_conflicts_and_half_set_pairs_exit_two(self):
        p = gate("--list", "--shard", "0/3", env={"GTEST_SHARD_INDEX": "1", "GTEST_TOTAL_SHARDS": "3"})
        one_line_error(self, p, "conflicting shards", "--shard 0/3", "GTEST_SHARD_INDEX=1")
        p = gate("--list", env={"GTEST_SHARD_INDEX": "0", "GTEST_TOTAL_SHARDS": "2",
                                "TEST_SHARD_INDEX": "0", "TEST_TOTAL_SHARDS": "3"})
        one_line_error(self, p, "conflicting shards", "TEST_TOTAL_SHARDS=3")
        p = gate("--list", env={"TEST_SHARD_INDEX": "1"})
        one_line_error(self, p, "TEST_SHARD_INDEX=1", "without TEST_TOTAL_SHARDS")
        p = gate("--list", env={"GTEST_SHARD_INDEX": "3", "GTEST_TOTAL_SHARDS": "3"})
        one_line_error(self, p, "GTEST_SHARD_INDEX=3 GTEST_TOTAL_SHARDS=3", "0 <= I < N")
        p = gate("--list", env={"GTEST_SHARD_INDEX": "0", "GTEST_TOTAL_SHARDS": "2",
                                "GTEST_SHARD_STATUS_FILE": os.path.join(self.tmp, "no", "such", "dir")})
        one_line_error(self, p, "GTEST_SHARD_STATUS_FILE=")
        render = os.path.join(BUILD, "render", "cavity_render")
        p = run([render, "--matrix", "ci", "--shard", "1/2", "--out", os.path.join(self.tmp, "r")],
                env={"TEST_SHARD_INDEX": "0", "TEST_TOTAL_SHARDS": "2"})
        one_line_error(self, p, "cavity_render: conflicting shards")
        self.assertFalse(os.path.exists(os.path.join(self.tmp, "r", "manifest.json")))

    def test_a_merged_gate_is_accepted_as_a_whole_one(self):
        # Two shards gated (as on two CI machines), merged, and the shards'
        # folders deleted: `baselines update` reads the merged folder's own
        # images, and the gate then passes against what it wrote.
        env = {"CAVITY_TEST_FLAKY": "/vk/compute$"}
        store = os.path.join(self.tmp, "no_store")
        shards = [os.path.join(self.tmp, f"s{i}") for i in range(2)]
        for i, d in enumerate(shards):
            gate("--filter", TWO, "--retries", "0", "--shard", f"{i}/2", "--out", d, "--store", store, env=env)
        merged = os.path.join(self.tmp, "merged")
        p = run([CAVITY, "gate", "merge", *shards, "--out", merged])
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        for d in shards:
            shutil.rmtree(d)
        for r in load(os.path.join(merged, "gate.json"))["results"]:
            for i in r["images"]:
                for key in ("new", "new_png", "diff_png"):
                    self.assertTrue(not i[key] or i[key].startswith(merged + "/images/"), i[key])
                    self.assertTrue(not i[key] or os.path.isfile(i[key]), i[key])
        base = os.path.join(self.tmp, "baselines")
        shutil.copytree(os.path.join(SOURCE, "baselines"), base)
        p = run([CAVITY, "baselines", "update", "--from", merged, "--baselines", base])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("1 baseline files updated", p.stdout)
        p = gate("--filter", TWO, "--retries", "0", "--baselines", base, "--out", os.path.join(self.tmp, "after"),
                 "--store", store, env=env)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        # A second merge into the same folder replaces its images whole.
        for i, d in enumerate(shards):
            gate("--filter", TWO, "--retries", "0", "--shard", f"{i}/2", "--out", d, "--store", store)
        p = run([CAVITY, "gate", "merge", *shards, "--out", merged])
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertEqual(sorted(os.listdir(merged)), ["gate.json", "images", "index.html", "junit.xml",
                                                       "status.json", "summary.md"])

    def test_update_says_when_one_baseline_cannot_hold_both_apis(self):
        # GL and Vulkan share a baseline file; where they rendered different
        # images, updating both took GL's and the next gate failed Vulkan,
        # whose update then failed GL: update says to approve by digest.
        g = os.path.join(self.tmp, "g")
        p = gate("--filter", TWO, "--retries", "0", "--out", g, "--store", os.path.join(self.tmp, "no_store"),
                 env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
        for args, note in (([], False), (["--filter", TWO], True)):
            base = os.path.join(self.tmp, "baselines" + str(note))
            shutil.copytree(os.path.join(SOURCE, "baselines"), base)
            p = run([CAVITY, "baselines", "update", "--from", g, "--baselines", base, *args])
            self.assertEqual(p.returncode, 0, p.stderr)
            self.assertEqual("note: 1 selected configuration rendered other images" in p.stdout, note, p.stdout)
            if note:
                self.assertIn(f"e.g. {VK} (the baseline takes {GL}'s)", p.stdout)
                self.assertIn(f"cavity baselines approve --from {g}", p.stdout)

    def test_judge_refuses_a_lost_shard_unless_told(self):
        # Shard 1 of 2 alone is half a verdict: refused, nothing written;
        # named with --shards it is judged; a wrong name is refused.
        render = os.path.join(BUILD, "render", "cavity_render")
        folder = os.path.join(self.tmp, "r1")
        p = run([render, "--matrix", "ci", "--filter", FILTER, "--shard", "1/2", "--out", folder])
        self.assertEqual(p.returncode, 0, p.stderr)
        out = os.path.join(self.tmp, "judged")
        p = run([CAVITY, "gate", "judge", folder, "--out", out, "--quiet"])
        one_line_error(self, p, "shards 1/2", "0/2 are missing", "--shards 1/2")
        self.assertFalse(os.path.exists(out), "nothing written")
        p = run([CAVITY, "gate", "judge", folder, "--shards", "0/2", "--out", out, "--quiet"])
        one_line_error(self, p, "--shards 0/2 names 0/2")
        p = run([CAVITY, "gate", "judge", folder, "--shards", "1/3", "--out", out, "--quiet"])
        one_line_error(self, p, "--shards 1/3: must be")
        self.assertFalse(os.path.exists(out), "nothing written")
        p = run([CAVITY, "gate", "judge", folder, "--shards", "1/2", "--out", out, "--quiet"])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(load(os.path.join(out, "gate.json"))["shard"], [1, 2])


class Flaky(Base):
    def test_planted_flake_is_reported_flaky_everywhere(self):
        out = os.path.join(self.tmp, "gate")
        p = gate("--filter", TWO, "--out", out, env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 0, "flaky alone is not fatal: " + p.stderr)
        self.assertIn(f"{VK}", p.stderr)
        self.assertRegex(p.stderr, re.escape(VK) + r" +flaky \(failed attempt 1, passed attempt 2\)")
        g = load(os.path.join(out, "gate.json"))
        self.assertEqual(g["counts"], {"flaky": 1, "pass": 1})
        v = {r["id"]: r for r in g["results"]}
        self.assertEqual(v[VK]["verdict"], "flaky")
        self.assertEqual(v[VK]["attempts"], 2)
        self.assertTrue(any("ao: " in f for f in v[VK]["first_failures"]))
        self.assertEqual(v[GL]["verdict"], "pass")
        with open(os.path.join(out, "junit.xml")) as f:
            junit = f.read()
        self.assertIn(f'name="{VK}/flaky"', junit)
        self.assertIn("<flakyFailure", junit)
        self.assertIn('failures="0"', junit)
        with open(os.path.join(out, "summary.md")) as f:
            summary = f.read()
        self.assertIn(f"- flaky: `{VK}`", summary)
        self.assertNotIn("all 2 configurations passed", summary)
        self.assertIn("- flaky: `", p.stdout)   # the console gets summary.md
        # The verdict survives gate.json: a merge of the shard keeps it.
        merged = os.path.join(self.tmp, "merged")
        p = run([CAVITY, "gate", "merge", out, "--out", merged])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(verdicts(os.path.join(merged, "gate.json"))[VK][0], "flaky")
        # The report's page shows the verdict it was given: the data inlined
        # in it is gate.json, and the page its script builds carries the badge
        # (last: without chromium the rest of this test is skipped).
        html = os.path.join(out, "index.html")
        self.assertEqual(report_data(html)["gate"], g)
        dom = rendered_dom(self, html)
        self.assertIn(f'data-id="{VK}" data-repetition="0" data-verdict="flaky"', dom)
        self.assertIn('<span class="badge">flaky</span>', dom)

    def test_without_retries_the_flake_is_a_failure(self):
        out = os.path.join(self.tmp, "gate")
        p = gate("--filter", TWO, "--retries", "0", "--out", out, env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 1, p.stderr)
        self.assertEqual(verdicts(os.path.join(out, "gate.json"))[VK][0], "fail")
        one_line_error(self, gate("--retries", "-1", "--out", out), "--retries -1", "0..100")
        one_line_error(self, gate("--filter", TWO, "--out", out, env={"CAVITY_TEST_FLAKY": "(["}), "CAVITY_TEST_FLAKY=([")


class Expectations(Base):
    def write(self, text, name="lavapipe.txt"):
        d = os.path.join(self.tmp, "expectations")
        os.makedirs(d, exist_ok=True)
        with open(os.path.join(d, name), "w") as f:
            f.write(text)
        return d

    def test_expected_failure_and_unexpected_pass(self):
        d = self.write("# planted by tests/test_fleet.py\ndevice .\n"
                       f"fail ^{re.escape(VK)}$ the test hook breaks it\n"
                       f"fail ^{re.escape(GL)}$ listed, but it passes\n")
        out = os.path.join(self.tmp, "gate")
        p = gate("--filter", TWO, "--retries", "0", "--expectations", d, "--out", out,
                 env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 1, "an unexpected pass fails the gate: " + p.stderr)
        g = load(os.path.join(out, "gate.json"))
        v = {r["id"]: r for r in g["results"]}
        self.assertEqual(v[VK]["verdict"], "expected-fail")
        self.assertFalse(v[VK]["fatal"])
        self.assertIn("lavapipe.txt:3: the test hook breaks it", v[VK]["expected_reason"])
        self.assertEqual(v[GL]["verdict"], "unexpected-pass")
        self.assertTrue(v[GL]["fatal"])
        with open(os.path.join(out, "junit.xml")) as f:
            junit = f.read()
        self.assertIn("<skipped message=\"expected failure", junit)
        self.assertIn(f'name="{GL}/expectation"', junit)
        with open(os.path.join(out, "summary.md")) as f:
            summary = f.read()
        self.assertIn("unexpected pass", summary)
        self.assertIn(f"- expected-fail: `{VK}`", summary)
        # Without the unexpected pass the expected failure alone exits 0.
        d = self.write(f"device .\nfail ^{re.escape(VK)}$ the test hook breaks it\n")
        p = gate("--filter", TWO, "--retries", "0", "--expectations", d, "--out", out,
                 env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 0, p.stderr)
        # `baselines update` does not accept an expected failure's image by
        # default; the same failure unlisted is accepted.
        base = os.path.join(self.tmp, "baselines")
        shutil.copytree(os.path.join(SOURCE, "baselines"), base)
        p = run([CAVITY, "baselines", "update", "--from", out, "--baselines", base])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("0 baseline files updated", p.stdout)
        plain = os.path.join(self.tmp, "plain")
        # No image store (as in a clone): the CPU images are judged against
        # the baseline files, which update replaces (a local store's
        # approved references would be accepted by approve instead).
        p = gate("--filter", TWO, "--retries", "0", "--out", plain, "--store", os.path.join(self.tmp, "no_store"),
                 env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 1, p.stderr)
        p = run([CAVITY, "baselines", "update", "--from", plain, "--baselines", base])
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertIn("1 baseline files updated", p.stdout)
        # A known flake that fails every attempt: reported, not fatal.
        d = self.write(f"device .\nflake /vk/compute$ the test hook breaks it\n")
        p = gate("--filter", TWO, "--retries", "0", "--expectations", d, "--out", out,
                 env={"CAVITY_TEST_FLAKY": "/vk/compute$"})
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual(verdicts(os.path.join(out, "gate.json"))[VK][0], "known-flake")
        # A file for another device class does not apply.
        d = self.write("device ^NVIDIA\nfail . every configuration\n")
        p = gate("--filter", TWO, "--expectations", d, "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr)
        self.assertEqual({x[0] for x in verdicts(os.path.join(out, "gate.json")).values()}, {"pass"})

    def test_bad_files_exit_two_naming_file_and_line(self):
        out = os.path.join(self.tmp, "gate")
        cases = [
            ("device .\nfail ^corner/(alchemy reason\n", ["lavapipe.txt:2", "'^corner/(alchemy'", "not a regular expression"]),
            ("device .\nfail ^corner/\n", ["lavapipe.txt:2", "the reason is required"]),
            ("device .\nfails ^corner/ why\n", ["lavapipe.txt:2", "'fails'"]),
            ("fail ^corner/ why\n", ["lavapipe.txt:1", "before the file's `device REGEX` line"]),
            ("# nothing\n", ["lavapipe.txt", "no `device REGEX` line"]),
            ("device (\n", ["lavapipe.txt:1", "device regex '('"]),
            ("device .\ndevice .\n", ["lavapipe.txt:2", "a second device line"]),
        ]
        for text, words in cases:
            d = self.write(text)
            p = gate("--filter", TWO, "--expectations", d, "--out", out)
            one_line_error(self, p, *words)
            self.assertFalse(os.path.exists(os.path.join(out, "gate.json")), text)
        # The files shipped in baselines/expectations/ are valid (one
        # configuration: a filter matching none is bad input itself).
        p = gate("--filter", "^corner/alchemy/n16/b4/full/160x90/vk/compute$", "--out", out)
        self.assertEqual(p.returncode, 0, p.stderr)


class Bisect(Base):
    ID = "corner/alchemy/n16/b4/full/160x90/vk/compute"

    def git(self, *args):
        p = subprocess.run(["git", "-C", self.repo, *args], capture_output=True, text=True)
        self.assertEqual(p.returncode, 0, p.stderr)
        return p.stdout.strip()

    def commit(self, message, value, builds=True):
        with open(os.path.join(self.repo, "value"), "w") as f:
            f.write(f"{value}\n")
        with open(os.path.join(self.repo, "build.sh"), "w") as f:
            f.write('set -e\nmkdir -p "$1"\ncp value fake_gate.py fake_run.py "$1/"\n' if builds else
                    'echo "build.sh: a syntax error in this commit" >&2\nexit 1\n')
        self.git("add", "-A")
        self.git("commit", "-qm", message)
        return self.git("rev-parse", "HEAD")

    def setUp(self):
        super().setUp()
        # A stand-in project with the shape of Cavity's loop: a build, and a
        # run that writes a cavity.gate/1 gate.json whose ao max abs error is
        # the commit's `value` (tolerance 0.1).
        self.repo = os.path.join(self.tmp, "repo")
        os.makedirs(os.path.join(self.repo, "baselines"))
        with open(os.path.join(self.repo, "baselines", "README"), "w") as f:
            f.write("stand-in\n")
        with open(os.path.join(self.repo, "fake_gate.py"), "w") as f:
            f.write('''import json, os, sys
build, out, cid = sys.argv[1:4]
v = float(open(os.path.join(build, "value")).read())
ok = v <= 0.1
img = {"image": "ao", "passed": ok, "metrics": {"max_abs": v, "rmse": v / 4, "ssim": 1 - v},
       "failures": [] if ok else ["max abs error %g > 0.1" % v], "digest": "x"}
gate = {"schema": "cavity.gate/1", "matrix": "ci", "exit_code": 0 if ok else 1,
        "results": [{"id": cid, "repetition": 0, "passed": ok, "verdict": "pass" if ok else "fail",
                     "error": "", "images": [img], "timings": []}]}
json.dump(gate, open(os.path.join(out, "gate.json"), "w"))
sys.exit(0 if ok else 1)
''')
        # And a run that writes a cavity.results/1 file whose ao pass takes
        # (1 + value) ms, give or take 0.05: judged by the real cavity compare.
        with open(os.path.join(self.repo, "fake_run.py"), "w") as f:
            f.write('''import json, os, sys
build, out, cid = sys.argv[1:4]
v = 1 + float(open(os.path.join(build, "value")).read())
samples = [v + 0.005 * k for k in range(10)]
run = {"id": cid, "clock": "gpu-timestamp", "frame": {"samples_ms": [2 + x for x in samples]},
       "passes": [{"name": "ao", "samples_ms": samples}, {"name": "blur", "samples_ms": [0.5 + 0.001 * k for k in range(10)]}]}
json.dump({"schema": "cavity.results/1", "runs": [run]}, open(os.path.join(out, "results.json"), "w"))
''')
        self.git("init", "-q")
        self.git("config", "user.email", "test@example.com")
        self.git("config", "user.name", "test")
        self.shas = [self.commit("one: the good start", 0.01),
                     self.commit("two: a harmless change", 0.02),
                     self.commit("three: the planted bug", 0.5),
                     self.commit("four: breaks the build", 0.5, builds=False),
                     self.commit("five: builds again", 0.5)]
        self.env = {"CAVITY_BISECT_BUILD": 'bash "$SRC/build.sh" "$BUILD"',
                    "CAVITY_BISECT_RUN": 'python3 "$BUILD/fake_gate.py" "$BUILD" "$OUT" "$ID"',
                    "CAVITY_BISECT_WORK": os.path.join(self.tmp, "work"), "TMPDIR": self.tmp}

    def test_names_the_third_commit(self):
        p = run([os.path.join(SOURCE, "scripts", "bisect.sh"), self.shas[0], self.shas[4], "--id", self.ID,
                 "--image", "ao"], env=self.env, cwd=self.repo)
        print(p.stdout, p.stderr)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn(f"first bad commit: {self.shas[2]} three: the planted bug", p.stdout)
        self.assertRegex(p.stdout, re.escape(self.shas[2][:12]) + r" bad +ao: max abs 0.5, RMSE 0.125")
        self.assertRegex(p.stdout, re.escape(self.shas[1][:12]) + r" good +ao: max abs 0.02")
        # The source checkout is untouched and the worktree is gone.
        self.assertEqual(self.git("rev-parse", "HEAD"), self.shas[4])
        self.assertEqual(len(self.git("worktree", "list").splitlines()), 1)
        self.assertFalse(os.path.exists(os.path.join(self.repo, ".git", "BISECT_LOG")))

    def test_pass_mode_names_the_third_commit_by_cavity_compare(self):
        env = dict(self.env, CAVITY_BISECT_RUN='python3 "$BUILD/fake_run.py" "$BUILD" "$OUT" "$ID"',
                   CAVITY_BISECT_COMPARE=CAVITY)
        p = run([os.path.join(SOURCE, "scripts", "bisect.sh"), self.shas[0], self.shas[4], "--id", self.ID,
                 "--pass", "ao"], env=env, cwd=self.repo)
        print(p.stdout, p.stderr)
        self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
        self.assertIn(f"first bad commit: {self.shas[2]} three: the planted bug", p.stdout)
        self.assertRegex(p.stdout, re.escape(self.shas[2][:12]) + r" bad +ao: 1.0\d+ -> 1.5\d+ ms, change \+4\d\.\d+%, p [0-9.e-]+, slower")
        self.assertRegex(p.stdout, re.escape(self.shas[1][:12]) + r" good .* same")

    def test_a_commit_that_does_not_build_is_skipped(self):
        self.git("checkout", "-q", self.shas[3])
        work = self.env["CAVITY_BISECT_WORK"]
        os.makedirs(os.path.join(work, "numbers"))
        p = run([sys.executable, os.path.join(SOURCE, "scripts", "bisect_step.py")], cwd=self.repo,
                env=dict(self.env, CAVITY_BISECT_ID=self.ID, CAVITY_BISECT_IMAGE="ao"))
        self.assertEqual(p.returncode, 125, p.stdout + p.stderr)
        self.assertIn("skip  does not build", p.stdout)
        self.git("checkout", "-q", self.shas[2])
        p = run([sys.executable, os.path.join(SOURCE, "scripts", "bisect_step.py")], cwd=self.repo,
                env=dict(self.env, CAVITY_BISECT_ID=self.ID, CAVITY_BISECT_IMAGE="ao"))
        self.assertEqual(p.returncode, 1, p.stdout + p.stderr)

    def test_bad_arguments_exit_two(self):
        b = os.path.join(SOURCE, "scripts", "bisect.sh")
        one_line_error(self, run([b, self.shas[0], self.shas[4]], cwd=self.repo), "--id: missing")
        one_line_error(self, run([b, self.shas[0], self.shas[4], "--id", self.ID, "--image", "depth"], cwd=self.repo),
                       "--image depth", "ao, ao_blur or color")
        one_line_error(self, run([b, "nosuch", self.shas[4], "--id", self.ID], cwd=self.repo), "GOOD nosuch")
        one_line_error(self, run([b, self.shas[4], self.shas[0], "--id", self.ID], cwd=self.repo), "not an ancestor")


SUITES = {"ctest_resources": CtestResources, "shard_protocols": ShardProtocols, "flaky": Flaky,
          "expectations": Expectations, "bisect": Bisect}

if __name__ == "__main__":
    if len(sys.argv) != 5 or sys.argv[1] not in SUITES:
        print("usage: test_fleet.py {" + ",".join(SUITES) + "} CAVITY SOURCE_DIR BUILD_DIR", file=sys.stderr)
        sys.exit(2)
    name, CAVITY, SOURCE, BUILD = sys.argv[1:5]
    suite = unittest.defaultTestLoader.loadTestsFromTestCase(SUITES[name])
    sys.exit(0 if unittest.TextTestRunner(verbosity=2).run(suite).wasSuccessful() else 1)
