#!/usr/bin/env python3
"""README's flag table for `cavity run` (section Running) lists exactly the
flags `cavity run --help` prints, which are generated from the declarations.

    readme_flags.py CAVITY SOURCE_DIR
"""
import re
import subprocess
import sys


def main():
    cavity, source = sys.argv[1], sys.argv[2]
    r = subprocess.run([cavity, "run", "--help"], capture_output=True, text=True)
    if r.returncode != 0 or not r.stdout:
        print(f"FAIL cavity run --help: exit {r.returncode}, stdout {len(r.stdout)} chars")
        sys.exit(1)
    helped = set(re.findall(r"^\s+(--[a-z_-]+)", r.stdout, re.M)) - {"--help"}
    readme = open(f"{source}/README.md").read()
    section = readme[readme.index("## Running"):readme.index("### Imported G-buffer")]
    rows = [l for l in section.splitlines() if l.startswith("| `--")]
    tabled = set()
    for row in rows:
        tabled.update(re.findall(r"`(--[a-z_-]+)`", row.split("|")[1]))
    missing, stale = sorted(helped - tabled), sorted(tabled - helped)
    for f in missing:
        print(f"FAIL {f}: printed by cavity run --help, not in README's flag table")
    for f in stale:
        print(f"FAIL {f}: in README's flag table, not a flag of cavity run --help")
    print(f"{len(helped)} flags; {len(missing) + len(stale)} failed")
    sys.exit(1 if missing or stale else 0)


if __name__ == "__main__":
    main()
