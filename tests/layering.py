#!/usr/bin/env python3
"""The harness's folders depend one way: a file in harness/<folder>/ includes
harness headers by folder path ("measure/timing.h"), only from its own folder
or a folder below it in LAYERS, and never a front end's header (cli/,
render/, bench/). Each folder's code lives in namespace cavity::<folder>.

    layering.py SOURCE_DIR        exit 0: all hold; 1: each break on one line
"""
import os
import re
import sys

# Bottom first: a folder may include itself and what is above it in this list.
LAYERS = ["core", "stats", "reference", "pipeline", "images", "plan", "measure",
          "render", "store", "gate", "compare", "report", "history"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
NAMESPACE = re.compile(r"^\s*namespace\s+([A-Za-z_][\w:]*)\s*\{(?!\})", re.M)


def files_under(root, exts=(".cpp", ".h")):
    for base, _, names in os.walk(root):
        for n in sorted(names):
            if n.endswith(exts):
                yield os.path.join(base, n)


def main():
    source = sys.argv[1]
    harness = os.path.join(source, "harness")
    lower = {name for root in ("backends", "kernels")
             for p in files_under(os.path.join(source, root), (".h",))
             for name in (os.path.relpath(p, os.path.join(source, root)),)}
    failures, checked = [], 0
    for folder in LAYERS:
        for path in files_under(os.path.join(harness, folder)):
            rel = os.path.relpath(path, source)
            text = open(path, encoding="utf-8").read()
            checked += 1
            for inc in INCLUDE.findall(text):
                head = inc.split("/")[0]
                if head in LAYERS and os.path.exists(os.path.join(harness, inc)):
                    if LAYERS.index(head) > LAYERS.index(folder):
                        failures.append(f"{rel}: includes \"{inc}\", and {head}/ is above {folder}/")
                elif inc in lower:
                    continue
                else:
                    failures.append(f"{rel}: includes \"{inc}\", which is no harness header by folder path "
                                    "nor a backends/ or kernels/ header")
            for ns in NAMESPACE.findall(text):
                if not ns.startswith("cavity") or ns == f"cavity::{folder}" or ns.startswith(f"cavity::{folder}::"):
                    continue  # a nested namespace (reference's screen, images' oiio) or the folder's own
                failures.append(f"{rel}: declares namespace {ns}, where {folder}/ is cavity::{folder}")
    for f in failures:
        print(f"FAIL {f}")
    print(f"layering: {checked} files; {len(failures)} failed")
    sys.exit(1 if failures or checked == 0 else 0)


if __name__ == "__main__":
    main()
