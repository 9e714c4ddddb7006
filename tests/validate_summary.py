#!/usr/bin/env python3
"""The gate's pull-request outputs read by real consumers: summary.md
rendered by cmark-gfm (GitHub's CommonMark with tables, Debian's cmark-gfm)
and status.json validated by python3-jsonschema against
harness/report/status.schema.json, for a gate that fails (a planted shader
edit through --kernel-source) and one that passes.

    validate_summary.py CAVITY SOURCE_DIR     exit 0: every check held
"""
import html.parser
import json
import os
import subprocess
import sys
import tempfile

import jsonschema

URL = "https://ci.example.org/artifacts/42/gate/index.html"
FILTER = "^corner/(alchemy|alchemy_fast|hemisphere)/n16/b4/(full|half)/160x90/(gl|vk)/compute$"


class Tables(html.parser.HTMLParser):
    """Rows of every <table> and the href of every link."""

    def __init__(self):
        super().__init__()
        self.rows, self.links, self.cell = [], [], None

    def handle_starttag(self, tag, attrs):
        if tag == "tr":
            self.rows.append([])
        elif tag in ("td", "th"):
            self.cell = ""
        elif tag == "a":
            self.links.append(dict(attrs).get("href"))

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.rows:
            self.rows[-1].append(self.cell.strip())
            self.cell = None

    def handle_data(self, data):
        if self.cell is not None:
            self.cell += data


def gate(cavity, source, out, extra):
    cmd = [cavity, "gate", "--matrix", "ci", "--filter", FILTER, "--retries", "0", "--quiet",
           "--baselines", os.path.join(source, "baselines"), "--out", out, "--report-url", URL] + extra
    return subprocess.run(cmd, capture_output=True, text=True)


def check(out, want_state, failures):
    schema = json.load(open(os.path.join(SOURCE, "harness", "report", "status.schema.json")))
    status = json.load(open(os.path.join(out, "status.json")))
    try:
        jsonschema.validate(status, schema)
    except jsonschema.ValidationError as e:
        failures.append(f"status.json: {e.message}")
    if status.get("state") != want_state:
        failures.append(f"status.json: state {status.get('state')}, want {want_state}")
    if status.get("target_url") != URL:
        failures.append(f"status.json: target_url {status.get('target_url')}")
    summary = open(os.path.join(out, "summary.md"), encoding="utf-8").read()
    lines = summary.splitlines()
    if len(lines) > 30:
        failures.append(f"summary.md: {len(lines)} lines, over 30")
    rendered = subprocess.run(["cmark-gfm", "-e", "table"], input=summary, capture_output=True, text=True, check=True).stdout
    parsed = Tables()
    parsed.feed(rendered)
    if URL not in parsed.links:
        failures.append(f"summary.md: no link to {URL} once rendered (links: {parsed.links})")
    return parsed, summary


def main():
    global SOURCE
    cavity, SOURCE = sys.argv[1], sys.argv[2]
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        edit = os.path.join(tmp, "bias_flipped.glsl")
        text = open(os.path.join(SOURCE, "kernels", "ao", "alchemy", "ssao_alchemy.glsl")).read()
        open(edit, "w").write(text.replace("- P.bias", "+ P.bias"))
        bad = os.path.join(tmp, "bad")
        r = gate(cavity, SOURCE, bad, ["--kernel-source", f"ssao_alchemy.glsl={edit}"])
        if r.returncode != 1:
            failures.append(f"planted edit: gate exit {r.returncode}, want 1: {r.stderr.strip()[-300:]}")
        else:
            parsed, summary = check(bad, "failure", failures)
            head = parsed.rows[0] if parsed.rows else []
            if head != ["kernel", "check", "configurations", "worst", "tolerance"]:
                failures.append(f"summary.md: table head {head}")
            body = [row for row in parsed.rows[1:] if row[0] != "…"]
            if not body or any(len(row) != 5 for row in body):
                failures.append(f"summary.md: table rows {body}")
            # Only alchemy was edited: every row is alchemy's, and a check that
            # fails on both APIs is one row counting both.
            if body and not all(row[0] == "alchemy" for row in body):
                failures.append(f"summary.md: a row for a kernel that was not edited: {body}")
            if body and not any(row[2].endswith("(gl+vk)") for row in body):
                failures.append(f"summary.md: no row merges GL and Vulkan: {body}")
            if edit not in summary:
                failures.append("summary.md: does not name the replaced kernel source")
        good = os.path.join(tmp, "good")
        r = gate(cavity, SOURCE, good, [])
        if r.returncode != 0:
            failures.append(f"unchanged: gate exit {r.returncode}, want 0: {r.stdout.strip()[-300:]}")
        else:
            parsed, _ = check(good, "success", failures)
            if parsed.rows:
                failures.append(f"summary.md: a passing gate has a failure table: {parsed.rows}")
    for f in failures:
        print(f"FAIL {f}")
    print(f"summary and status: {2} gate runs; {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
