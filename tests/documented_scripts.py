#!/usr/bin/env python3
"""Every script that README.md or docs/ names is run by a test.

A script the docs give a user and no test runs rots unseen: an edit to a
kernel or a flag breaks it, and the first to notice is the user who follows
the docs. This check reads every script name in README.md and docs/*.md
(a path under scripts/, or a bare NAME.sh / NAME.py that exists under
scripts/), and requires for each an entry in RUN_BY below: the test files
that run it. Each such file must name the script, and must itself be run by
ctest (named in tests/CMakeLists.txt), so that a script dropped from its
test, or a test dropped from ctest, fails here. A RUN_BY entry for a script
that no longer exists fails too.

    documented_scripts.py SOURCE_DIR     exit 0: all hold; 1: each break on one line
"""
import os
import re
import sys

# script (relative to the repository root) -> test files that run it, or the
# CI entry point that does. GPU scripts run as dry runs on the CPU renderers.
RUN_BY = {
    "scripts/setup.sh": ["scripts/test.sh"],  # which .ci/run runs on every CI run
    "scripts/test.sh": [".ci/run"],
    "scripts/run.sh": ["tests/test_bundle.py"],
    "scripts/bundle.sh": ["tests/test_bundle.py", "tests/gpu_scripts.py"],
    "scripts/gpu_env.sh": ["tests/gpu_scripts.py"],
    "scripts/gpu_render.sh": ["tests/gpu_scripts.py"],
    "scripts/gpu_references.sh": ["tests/gpu_scripts.py"],
    "scripts/gpu_store_run.sh": ["tests/gpu_scripts.py"],
    "scripts/gpu_sweep.sh": ["tests/gpu_scripts.py"],
    "scripts/gpu_history.sh": ["tests/gpu_scripts.py"],
    "scripts/history_bundle.sh": ["tests/gpu_scripts.py"],
    "scripts/history_ingest.sh": ["tests/gpu_scripts.py"],
    "scripts/planted_defects.sh": ["tests/planted_defects.py", "tests/gpu_scripts.py"],
    "scripts/bisect.sh": ["tests/test_fleet.py"],
    "scripts/bisect_step.py": ["tests/test_fleet.py"],
    "scripts/ctest_resources.py": ["tests/test_fleet.py"],
    "scripts/ctest_gate_shard.sh": ["tests/test_fleet.py"],
    "scripts/update_budgets.py": ["tests/test_gate_inputs.cpp"],
    "scripts/hooks/commit-msg": ["tests/commit_msg_hook.py"],
    "scripts/charts/charts.py": ["scripts/charts/test_charts.py"],
    "scripts/charts/floor_table.py": ["scripts/charts/test_charts.py"],
    "scripts/charts/gate_metrics.py": ["scripts/charts/test_charts.py"],
}

PATH_REF = re.compile(r"\bscripts/[\w./-]*[\w-](?![\w*])")   # not a glob (scripts/gpu_*.sh)
BARE_REF = re.compile(r"(?<![\w/.-])([\w-]+\.(?:sh|py))\b")


def documented(source):
    """The scripts the README and docs/ name, as repository paths, with where."""
    by_name = {}
    for base, dirs, names in os.walk(os.path.join(source, "scripts")):
        dirs[:] = [d for d in dirs if d != "__pycache__"]
        for n in names:
            by_name.setdefault(n, []).append(os.path.relpath(os.path.join(base, n), source))
    pages = [os.path.join(source, "README.md")] + sorted(
        os.path.join(source, "docs", n) for n in os.listdir(os.path.join(source, "docs")) if n.endswith(".md"))
    found = {}
    for page in pages:
        rel = os.path.relpath(page, source)
        for lineno, line in enumerate(open(page, encoding="utf-8"), 1):
            for ref in PATH_REF.findall(line):
                path = os.path.join(source, ref)
                if os.path.isfile(path):
                    found.setdefault(ref, f"{rel}:{lineno}")
                elif not os.path.isdir(path):
                    found.setdefault(ref, f"{rel}:{lineno}")   # named, but missing: reported below
            for name in BARE_REF.findall(line):
                for ref in by_name.get(name, []):
                    found.setdefault(ref, f"{rel}:{lineno}")
    return found


def main():
    source = os.path.abspath(sys.argv[1])
    ctest = open(os.path.join(source, "tests", "CMakeLists.txt"), encoding="utf-8").read()
    failures = []
    refs = documented(source)
    for ref, where in sorted(refs.items()):
        if not os.path.isfile(os.path.join(source, ref)):
            failures.append(f"{where}: names {ref}, which does not exist")
            continue
        tests = RUN_BY.get(ref)
        if not tests:
            failures.append(f"{where}: names {ref}, and no test runs it (add it to RUN_BY with the test that does)")
            continue
        for t in tests:
            path = os.path.join(source, t)
            if not os.path.isfile(path):
                failures.append(f"{ref}: its test {t} does not exist")
                continue
            if os.path.basename(ref) not in open(path, encoding="utf-8").read():
                failures.append(f"{ref}: {t} does not name it, so it does not run it")
            if t not in (".ci/run", "scripts/test.sh") and os.path.basename(t) not in ctest:
                failures.append(f"{ref}: {t} is not run by ctest (tests/CMakeLists.txt does not name it)")
    for ref in sorted(RUN_BY):
        if not os.path.isfile(os.path.join(source, ref)):
            failures.append(f"RUN_BY names {ref}, which does not exist")
    for f in failures:
        print(f"FAIL {f}")
    print(f"documented scripts: {len(refs)} named in README.md and docs/; {len(failures)} failed")
    sys.exit(1 if failures or not refs else 0)


if __name__ == "__main__":
    main()
