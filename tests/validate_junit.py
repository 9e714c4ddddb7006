#!/usr/bin/env python3
"""junit.xml read by real consumers: python3-xmlschema validates it against
tests/data/junit.xsd (what both the Jenkins xunit plugin's and the Ant JUnit
schemas require), and python3-junitparser, the parser behind several CI
report tools, reads back the counts, each failure's text and the times.

    validate_junit.py CAVITY SOURCE_DIR

A gate of two configurations runs against a copy of the baselines in which
one configuration's composite baseline is another scene's, so that the report
holds failures as well as passes.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import junitparser
import xmlschema

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from baselines_copy import drop_cpu_approvals  # noqa: E402

FULL = "corner/alchemy/n16/b4/full/160x90"
OTHER = "slats/alchemy/n16/b4/full/160x90"


def main():
    cavity, source = sys.argv[1], sys.argv[2]
    schema = xmlschema.XMLSchema(os.path.join(source, "tests", "data", "junit.xsd"))
    with tempfile.TemporaryDirectory() as tmp:
        base = os.path.join(tmp, "baselines")
        shutil.copytree(os.path.join(source, "baselines"), base, ignore=shutil.ignore_patterns("images"))
        for key in (FULL, OTHER):
            shutil.copytree(os.path.join(source, "baselines", "images", key), os.path.join(base, "images", key))
        shutil.copy(os.path.join(base, "images", OTHER, "color.png"), os.path.join(base, "images", FULL, "color.png"))
        drop_cpu_approvals(base)
        # No timing budgets: this test is about the report, and a CPU
        # renderer's pass over its budget under a loaded ctest (seen on the
        # sanitizer build) would add a third failed case that no image made.
        with open(os.path.join(base, "budgets.json")) as f:
            budgets = json.load(f)
        budgets["devices"] = []
        with open(os.path.join(base, "budgets.json"), "w") as f:
            json.dump(budgets, f)
        out = os.path.join(tmp, "gate")
        r = subprocess.run([cavity, "gate", "--matrix", "ci", "--baselines", base, "--retries", "0", "--filter",
                            f"^{FULL}/(gl|vk)/compute$", "--out", out], capture_output=True, text=True)
        if r.returncode != 1:
            sys.exit(f"the gate exited {r.returncode}, expected 1 (a regression): {r.stderr}")
        path = os.path.join(out, "junit.xml")
        errors = list(schema.iter_errors(path))
        if errors:
            sys.exit(f"{path} does not validate against tests/data/junit.xsd:\n" + "\n".join(str(e) for e in errors[:5]))

        gate = json.load(open(os.path.join(out, "gate.json")))
        failing = sum(1 for c in gate["results"] for i in c["images"] if i["failures"])
        xml = junitparser.JUnitXml.fromfile(path)
        suites = list(xml) if isinstance(xml, junitparser.JUnitXml) else [xml]
        cases = [c for s in suites for c in s]
        failed = [c for c in cases if any(isinstance(x, junitparser.Failure) for x in c.result)]
        if len(failed) != failing or failing != 2:
            sys.exit(f"junitparser reads {len(failed)} failed cases, gate.json has {failing} failing images (expected 2)")
        for c in failed:
            f = next(x for x in c.result if isinstance(x, junitparser.Failure))
            if not (f.text or "").strip() or not f.message:
                sys.exit(f"{c.name}: a failure without text or message (GitLab shows the text, Jenkins the message)")
            if "color" not in c.name:
                sys.exit(f"{c.name}: only the composite was changed")
        if sum(s.tests for s in suites) != len(cases) or sum(s.failures for s in suites) != failing:
            sys.exit("the suite's counts disagree with its cases")
        times = re.findall(r'time="([^"]*)"', open(path).read())
        if not times or any(not re.fullmatch(r"\d+\.\d{3}", t) for t in times):
            sys.exit(f"times must have three decimals: {times[:5]}")
        print(f"{path}: valid; {len(cases)} cases, {len(failed)} failures with text, {len(times)} times")


if __name__ == "__main__":
    main()
