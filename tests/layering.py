#!/usr/bin/env python3
"""Dependencies point one way, and CMake's link lines are the one map of them.

The map is read from CMake's file API (BUILD_DIR/.cmake/api/v1/reply/, asked
for by the top-level CMakeLists.txt): each target, the folder its sources are
in, the include directories its link line gives it, and the targets it
depends on. From that map:

  - the link graph has no cycle;
  - every `#include "..."` of a product file resolves to a header of its own
    folder, of a folder whose target its target links (directly or through
    others), or of an include directory its link line gives it (base/, the
    GPU interface): a header of a folder it does not link fails, even where a
    shared include root (harness/) would let it compile;
  - no `using namespace` directive opens another folder's namespace: a file
    names what it uses from below (qualified, or by a using-declaration);
  - each harness folder's code is in namespace cavity::<folder>;
  - no product file (anything outside the measurement notebook) names the
    notebook's folder: the product never reads it;
  - docs/architecture.md's drawn map is this map: `layering.py --draw
    BUILD_DIR` prints it, and the page holds it between its markers.

    layering.py SOURCE_DIR BUILD_DIR          exit 0: all hold; 1: each break on one line
    layering.py --draw BUILD_DIR              the map as docs/architecture.md shows it
"""
import glob
import json
import os
import re
import subprocess
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
NAMESPACE = re.compile(r"^\s*namespace\s+([A-Za-z_][\w:]*)\s*\{(?!\})", re.M)
USING_DIRECTIVE = re.compile(r"^\s*using\s+namespace\s+([A-Za-z_][\w:]*)\s*;", re.M)
NOTEBOOK = "lab"   # the measurement notebook's top-level folder
NOTEBOOK_REF = re.compile(r"(?<![\w./-])" + NOTEBOOK + "/")
# The one include that is no link, and why: the runner (harness/measure)
# calls the image-file functions that each binary supplies, cavity through
# cavity_images and cavity_render through render/no_image_files.cpp (errors
# it never reaches), so that cavity_render carries no OpenImageIO.
SEAMS = {"cavity_measure": ("cavity_images",)}
BEGIN, END = "<!-- drawn by tests/layering.py", "<!-- end of the drawn map -->"


def read_codemodel(build):
    """{target: {"type", "folders", "includes", "deps"}} from CMake's file API."""
    reply = os.path.join(build, ".cmake", "api", "v1", "reply")
    indexes = sorted(glob.glob(os.path.join(reply, "index-*.json")))
    if not indexes:
        sys.exit(f"layering: {reply}: no CMake file-API reply; scripts/setup.sh asks for one before configuring "
                 "(or configure once more: the top-level CMakeLists.txt writes the query)")
    index = json.load(open(indexes[-1]))
    model = next(o for o in index["objects"] if o["kind"] == "codemodel")
    code = json.load(open(os.path.join(reply, model["jsonFile"])))
    source, build_root = code["paths"]["source"], code["paths"]["build"]
    config = code["configurations"][0]
    by_id, targets = {}, {}
    for t in config["targets"]:
        tj = json.load(open(os.path.join(reply, t["jsonFile"])))
        # A build step with no code (the version stamp, the embedded
        # kernels' generator) orders the build; it is no layer.
        if tj["type"] == "UTILITY":
            continue
        # A unity build's batch files are in the build folder, and CMake does
        # not mark them generated: they name no folder of the product.
        srcs = [s["path"] for s in tj.get("sources", [])
                if not s.get("isGenerated") and not os.path.isabs(s["path"])
                and not os.path.join(source, s["path"]).startswith(build_root + "/")]
        includes = set()
        for g in tj.get("compileGroups", []):
            for inc in g.get("includes", []):
                if inc["path"].startswith(source + "/"):
                    includes.add(os.path.relpath(inc["path"], source))
        by_id[t["id"]] = tj["name"]
        targets[tj["name"]] = {"type": tj["type"], "folders": sorted({os.path.dirname(s) for s in srcs}),
                               "includes": includes, "dep_ids": [d["id"] for d in tj.get("dependencies", [])]}
    for t in targets.values():
        t["deps"] = {by_id[i] for i in t.pop("dep_ids") if i in by_id}
    return source, targets


def closure(targets, name, seen=None):
    seen = set() if seen is None else seen
    for d in targets[name]["deps"]:
        if d not in seen:
            seen.add(d)
            closure(targets, d, seen)
    return seen


def product_targets(targets):
    """The product's targets: every one but the tests'."""
    return {n: t for n, t in targets.items() if not any(f == "tests" or f.startswith("tests/") for f in t["folders"])}


def draw(targets):
    """The map: each product target's folder, its layer (0 at the bottom:
    the longest chain of links beneath it) and what it links directly (the
    links no other link already implies)."""
    prod = product_targets(targets)
    full = {n: closure(targets, n) & set(prod) for n in prod}
    direct = {n: {d for d in full[n] if not any(d in full[o] for o in full[n] if o != d)} for n in prod}
    layer = {}

    def depth(n):
        if n not in layer:
            layer[n] = 1 + max((depth(d) for d in direct[n]), default=-1)
        return layer[n]

    rows = sorted(prod, key=lambda n: (-depth(n), prod[n]["folders"][0] if prod[n]["folders"] else n))
    lines = [BEGIN + " from CMake's link lines; edit those, then run `tests/layering.py --draw build` -->",
             "", "| layer | folder | target | links directly |", "| ---: | --- | --- | --- |"]
    for n in rows:
        folders = ", ".join(f"`{f}/`" for f in prod[n]["folders"]) or "(headers)"
        uses = ", ".join(sorted(direct[n])) or "nothing of ours"
        lines.append(f"| {depth(n)} | {folders} | {n} | {uses} |")
    lines += ["", END]
    return "\n".join(lines) + "\n"


def owner_of(folder, folder_owner):
    """The target whose sources are in `folder` itself (not a parent's)."""
    return folder_owner.get(folder)


def resolve(source, including_file, inc, include_dirs):
    here = os.path.dirname(including_file)
    for base in [here] + sorted(include_dirs):
        p = os.path.normpath(os.path.join(base, inc))
        if os.path.isfile(os.path.join(source, p)):
            return p
    return None


def tracked(source):
    out = subprocess.run(["git", "-C", source, "ls-files"], capture_output=True, text=True)
    if out.returncode != 0:
        return None
    return out.stdout.split("\n")


def check(source, build):
    source_model, targets = read_codemodel(build)
    failures = []

    # No cycle: a target in its own closure.
    for n in targets:
        if n in closure(targets, n):
            failures.append(f"the link graph has a cycle through {n}")

    # Each folder is one target's (the tests' support library aside).
    folder_owner = {}
    for n, t in sorted(targets.items(), key=lambda kv: (kv[1]["type"] != "STATIC_LIBRARY", kv[0])):
        if t["type"] == "EXECUTABLE" and any(f.startswith("tests") for f in t["folders"]):
            continue
        for f in t["folders"]:
            folder_owner.setdefault(f, n)

    # A folder of several targets (harness/images: the library and the
    # OpenImageIO module it loads) may use what any of them links.
    folder_allowed = {}
    for n, t in targets.items():
        for f in t["folders"]:
            folder_allowed.setdefault(f, set()).update(closure(targets, n) | {n})

    checked = 0
    for n, t in sorted(targets.items()):
        allowed = set().union(*(folder_allowed[f] for f in t["folders"])) if t["folders"] else {n}
        allowed |= set().union(*(closure(targets, s) for s in SEAMS.get(n, ())), set(SEAMS.get(n, ())))
        for folder in t["folders"]:
            if folder.startswith("tests"):
                continue
            for name in sorted(os.listdir(os.path.join(source, folder))):
                if not name.endswith((".cpp", ".h")):
                    continue
                rel = os.path.join(folder, name)
                text = open(os.path.join(source, rel), encoding="utf-8").read()
                checked += 1
                for inc in INCLUDE.findall(text):
                    hit = resolve(source, rel, inc, t["includes"])
                    if hit is None:
                        failures.append(f"{rel}: includes \"{inc}\", which no include directory of {n} holds")
                        continue
                    where = os.path.dirname(hit)
                    if where == folder or where in t["includes"]:
                        continue
                    owner = owner_of(where, folder_owner)
                    if owner is None or owner not in allowed:
                        failures.append(f"{rel}: includes \"{inc}\" ({where}/), whose target "
                                        f"{owner or '(none)'} {n} does not link")
                own = folder.split("/", 1)[1] if folder.startswith("harness/") else None
                for ns in USING_DIRECTIVE.findall(text):
                    ns = ns.removeprefix("::")
                    if ns.startswith("cavity") and ns != f"cavity::{own}":
                        failures.append(f"{rel}: `using namespace {ns};` opens another folder's namespace; "
                                        "name what it uses (qualified, or a using-declaration)")
                if own:
                    for ns in NAMESPACE.findall(text):
                        if not ns.startswith("cavity") or ns == f"cavity::{own}" or ns.startswith(f"cavity::{own}::"):
                            continue
                        failures.append(f"{rel}: declares namespace {ns}, where {folder}/ is cavity::{own}")

    # The product never reads the notebook: no file outside it names it.
    files = tracked(source)
    if files is None:
        failures.append(f"{source}: not a git checkout; cannot list the product's files")
        files = []
    for f in files:
        if not f or f.startswith(NOTEBOOK + "/") or not os.path.isfile(os.path.join(source, f)):
            continue
        try:
            text = open(os.path.join(source, f), encoding="utf-8").read()
        except UnicodeDecodeError:
            continue
        for lineno, line in enumerate(text.splitlines(), 1):
            if NOTEBOOK_REF.search(line):
                failures.append(f"{f}:{lineno}: names the measurement notebook ({NOTEBOOK}/); the product never reads "
                                "it: cite a study by its folder name alone")

    # docs/architecture.md holds the drawn map.
    page = open(os.path.join(source, "docs", "architecture.md"), encoding="utf-8").read()
    start, end = page.find(BEGIN), page.find(END)
    drawn = draw(targets)
    if start < 0 or end < 0:
        failures.append("docs/architecture.md: no drawn map (its markers are missing)")
    elif page[start:end + len(END)] + "\n" != drawn:
        failures.append("docs/architecture.md: the drawn map differs from CMake's link lines; "
                        "paste `tests/layering.py --draw BUILD_DIR` between its markers")

    for f in failures:
        print(f"FAIL {f}")
    print(f"layering: {len(targets)} targets, {checked} files, {len(files)} tracked files; {len(failures)} failed")
    return 1 if failures or checked == 0 else 0


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "--draw":
        _, targets = read_codemodel(sys.argv[2])
        sys.stdout.write(draw(targets))
        return 0
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    return check(os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]))


if __name__ == "__main__":
    sys.exit(main())
