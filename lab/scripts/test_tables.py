#!/usr/bin/env python3
"""Tests for the lab's table scripts (lab/scripts/), on the recorded studies in
lab/. Run by hand, not by CI (the product's tests never read lab/):

    python3 lab/scripts/test_tables.py
    python3 -m unittest lab/scripts/test_tables.py

The scripts read plain or gzip JSON through scripts/charts/cavity_json.py,
which each puts on sys.path from the repository root; verdict_table.py and
ab_rounds.py also need a built `cavity` (--cavity), so only their command
lines are checked here.
"""

import glob
import os
import subprocess
import sys
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
LAB = os.path.dirname(HERE)


def run(script, *args):
    return subprocess.run([sys.executable, os.path.join(HERE, script), *args], capture_output=True, text=True,
                          timeout=120, cwd="/")   # from anywhere: the scripts find cavity_json themselves


class Tables(unittest.TestCase):
    def test_sync_table_reads_gzip(self):
        """The narrow/full barrier rounds of 2026-12-02_h200_sync (X.json.gz)."""
        r = run("sync_table.py", os.path.join(LAB, "2026-12-02_h200_sync"))
        self.assertEqual(r.returncode, 0, r.stderr)
        lines = r.stdout.splitlines()
        self.assertGreater(len(lines), 3)
        self.assertEqual(lines[0], "| configuration | narrow ms (round 1 / 2) | full ms (round 1 / 2) | full / narrow |")
        self.assertTrue(any(l.startswith("| corner/alchemy/n16/b4/full/1920x1080/vk/compute |") for l in lines), r.stdout)

    def test_planted_ratios(self):
        """The Vulkan planted defects of 2026-12-02_h200_store: every one fails where it was planted,
        as that study's README says (alchemy_bias 4 of 4, worst 5.1x)."""
        manifests = sorted(glob.glob(os.path.join(LAB, "2026-12-02_h200_store", "vk", "planted", "*.json")))
        self.assertTrue(manifests)
        r = run("planted_ratios.py", *manifests)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = {l.split(" | ")[0][2:]: l for l in r.stdout.splitlines()[2:]}
        self.assertEqual(sorted(rows), sorted(os.path.basename(m)[:-5] for m in manifests))
        self.assertIn("| alchemy_bias | 4 of 4 | 12 / 12 | 5.1x | differing_share |", r.stdout)

    def test_command_lines(self):
        """Each script starts from anywhere (cavity_json found from the repository root)."""
        for script in ("ab_rounds.py", "plant_calibrate.py", "verdict_table.py"):
            r = run(script, "--help")
            self.assertEqual(r.returncode, 0, (script, r.stderr))
            self.assertIn("usage", r.stdout.lower(), script)


if __name__ == "__main__":
    unittest.main()
