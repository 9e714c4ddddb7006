#!/usr/bin/env python3
"""Code a reader can hold in their head: no C++ file outside tests/ over 400
lines, and no function over 80, measured with Universal Ctags (Debian's
universal-ctags) from each function's first line to its closing brace.
Generated sources (the embedded kernels and report page) live in the build
folder and are not looked at.

    code_size.py SOURCE_DIR       exit 0: all within; 1: one line per excess
"""
import os
import subprocess
import sys

FOLDERS = ["backends", "kernels", "harness", "cli", "render", "bench"]
MAX_FILE_LINES, MAX_FUNCTION_LINES = 400, 80


def main():
    source = sys.argv[1]
    files = [os.path.join(base, n) for folder in FOLDERS
             for base, _, names in os.walk(os.path.join(source, folder))
             for n in sorted(names) if n.endswith((".cpp", ".h"))]
    failures = []
    for path in files:
        lines = sum(1 for _ in open(path, encoding="utf-8"))
        if lines > MAX_FILE_LINES:
            failures.append(f"{os.path.relpath(path, source)}: {lines} lines, over {MAX_FILE_LINES}")
    tags = subprocess.run(["ctags", "--languages=C++", "--c++-kinds=f", "--fields=+ne", "-o", "-", *files],
                          capture_output=True, text=True, check=True).stdout
    functions = 0
    for row in tags.splitlines():
        cols = row.split("\t")
        fields = dict(c.split(":", 1) for c in cols[3:] if ":" in c)
        if "line" not in fields or "end" not in fields:
            continue
        functions += 1
        length = int(fields["end"]) - int(fields["line"]) + 1
        if length > MAX_FUNCTION_LINES:
            failures.append(f"{os.path.relpath(cols[1], source)}:{fields['line']}: {cols[0]} is {length} lines, "
                            f"over {MAX_FUNCTION_LINES}")
    for f in failures:
        print(f"FAIL {f}")
    print(f"code size: {len(files)} files, {functions} functions; {len(failures)} failed")
    sys.exit(1 if failures or functions == 0 else 0)


if __name__ == "__main__":
    main()
