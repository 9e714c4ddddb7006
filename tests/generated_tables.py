#!/usr/bin/env python3
"""The kernel tables in README.md and docs/kernels.md against the packages.

    generated_tables.py CAVITY SOURCE_DIR [--write]

Each table sits between a marker that names the command which prints it,
`<!-- generated: cavity kernels list --markdown TABLE -->`, and
`<!-- generated: end -->`. The command reads the kernel packages (the
built-in ones are embedded in the binary), so a kernel added, renamed or
re-described as a package shows in the docs only as the packages say it.
Exit 0 when every table equals what its command prints, 1 otherwise (the
difference printed); --write rewrites the tables instead.
"""
import difflib
import os
import re
import subprocess
import sys

BLOCK = re.compile(r"(<!-- generated: cavity kernels list --markdown (\w+) -->\n)(.*?)(<!-- generated: end -->)", re.S)
FILES = ["README.md", "docs/kernels.md"]


def main():
    args = [a for a in sys.argv[1:] if a != "--write"]
    write = "--write" in sys.argv[1:]
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    cavity, source = args
    bad = 0
    found = 0
    for name in FILES:
        path = os.path.join(source, name)
        text = open(path, encoding="utf-8").read()

        def regenerate(m):
            nonlocal bad, found
            found += 1
            table = subprocess.run([cavity, "kernels", "list", "--markdown", m.group(2)], check=True,
                                   capture_output=True, text=True).stdout
            if m.group(3) != table and not write:
                bad += 1
                print(f"{name}: the '{m.group(2)}' table differs from `cavity kernels list --markdown {m.group(2)}`"
                      " (tests/generated_tables.py CAVITY SOURCE --write rewrites it):")
                sys.stdout.writelines(difflib.unified_diff(m.group(3).splitlines(True), table.splitlines(True),
                                                           "in " + name, "from the packages"))
            return m.group(1) + table + m.group(4)

        new = BLOCK.sub(regenerate, text)
        if write and new != text:
            open(path, "w", encoding="utf-8").write(new)
    # A check that found no table checked nothing.
    if found != 2:
        print(f"expected the 2 generated tables (README.md, docs/kernels.md), found {found}")
        return 1
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
