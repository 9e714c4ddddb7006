#!/usr/bin/env python3
"""`cavity quality --out` as a reader sees it, through the binary:

  - quality.json gives each row its MAE's 95% interval (low <= MAE <= high),
    and `tied_with` names the better kernel a row cannot be told from;
  - quality.html holds, per scene, the truth and every row's AO and signed
    error map, each drawn by its script (headless Chromium's DOM);
  - the error map's sign is the seeds' convention: a kernel whose mean AO is
    above the truth's (too little occlusion) is mostly orange (lighter), one
    below it mostly blue.

    test_quality_page.py BUILD_DIR
"""
import base64
import json
import os
import re
import subprocess
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_fleet import rendered_dom  # noqa: E402

BUILD = None


class QualityPage(unittest.TestCase):
    def test_error_maps_and_intervals(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "q")
            p = subprocess.run([os.path.join(BUILD, "harness", "cavity"), "quality", "--kernel",
                                "alchemy,alchemy_fast,hemisphere,gtao", "--samples", "16", "--scene", "corner,slats",
                                "--res", "160x90", "--quiet", "--out", out], capture_output=True, text=True, timeout=600)
            self.assertEqual(p.returncode, 0, p.stdout + p.stderr)
            doc = json.load(open(os.path.join(out, "quality.json")))
            rows = doc["rows"]
            self.assertEqual(len(rows), 8)
            for r in rows:
                self.assertLessEqual(r["mae_low"], r["mae"], r)
                self.assertLessEqual(r["mae"], r["mae_high"], r)
                if r["tied_with"]:
                    better = r["tied_with"].split("/n")[0]
                    mate = next(o for o in rows if o["scene"] == r["scene"] and o["kernel"] == better)
                    self.assertLessEqual(mate["mae"], r["mae"])
            # alchemy_fast is alchemy on a pyramid: on corner their errors cannot be told apart.
            fast = next(r for r in rows if r["scene"] == "corner" and r["kernel"] == "alchemy_fast")
            self.assertEqual(fast["tied_with"], "alchemy/n16", fast)

            html = open(os.path.join(out, "quality.html")).read()
            data = json.loads(re.search(r'id="quality-data">(.*?)</script>', html, re.S).group(1))
            self.assertEqual(data["doc"], doc)
            checked = 0
            for r in rows:
                m = data["maps"][r["scene"]]
                err = base64.b64decode(m["kernels"][f"{r['kernel']}/n16"]["error"])
                self.assertEqual(len(err), 3 * m["width"] * m["height"])
                px = [err[i:i + 3] for i in range(0, len(err), 3)]
                orange = sum(1 for c in px if c[0] > c[2] + 20)
                blue = sum(1 for c in px if c[2] > c[0] + 20)
                bias = r["mean_ao"] - r["mean_truth"]
                if abs(bias) > 0.02:   # a clear bias: the map leans its way
                    self.assertEqual(orange > blue, bias > 0, (r, orange, blue))
                    checked += 1
            self.assertGreater(checked, 0, "no row with a clear bias to check the sign on")

            dom = rendered_dom(self, os.path.join(out, "quality.html"))
            for scene in ("corner", "slats"):
                self.assertIn(f'id="truth-{scene}"', dom)
                for r in rows:
                    if r["scene"] != scene:
                        continue
                    for kind in ("ao", "error"):
                        self.assertIn(f'id="{kind}-{scene}-{r["kernel"]}/n16"', dom)
            self.assertIn("cannot be told from alchemy/n16", dom)

    def test_an_ao_of_nan_fails_and_says_where(self):
        # An edited kernel that writes NaN: its row has no error to rank, so
        # the run exits 1 naming the row, and still writes its files.
        src = open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "kernels", "ao", "alchemy",
                                "ssao_alchemy.glsl")).read()
        self.assertIn("write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));", src)
        with tempfile.TemporaryDirectory() as tmp:
            edited = os.path.join(tmp, "nan.glsl")
            with open(edited, "w") as f:
                f.write(src.replace("write_ao(pixel, vec4(A, 0.0, 0.0, 0.0));",
                                    "write_ao(pixel, vec4(uintBitsToFloat(0x7fc00000u), 0.0, 0.0, 0.0));"))
            out = os.path.join(tmp, "q")
            p = subprocess.run([os.path.join(BUILD, "harness", "cavity"), "quality", "--kernel", "alchemy",
                                "--samples", "8", "--scene", "corner", "--res", "64x36", "--quiet",
                                "--kernel-source", "ssao_alchemy.glsl=" + edited, "--out", out],
                               capture_output=True, text=True, timeout=600)
            self.assertEqual(p.returncode, 1, p.stdout + p.stderr)
            self.assertIn("corner/alchemy/n8: the AO holds NaN or infinity", p.stderr)
            # ... and its largest error is not a finite pixel's.
            row = json.load(open(os.path.join(out, "quality.json")))["rows"][0]
            self.assertIsNone(row["max_abs"], row)
            self.assertTrue(os.path.exists(os.path.join(out, "quality.json")))
            self.assertTrue(os.path.exists(os.path.join(out, "quality.html")))


if __name__ == "__main__":
    BUILD = sys.argv.pop(1)
    unittest.main()
