#!/usr/bin/env python3
"""The gate's coverage check, `cavity kernels coverage`, through the binary:

  - the stored CPU matrices (ci and gpu-cpu) reach every path every kernel
    declares, and say how many;
  - a matrices.json with one group taken out fails (exit 1) with one line
    that names the paths only that group reached: the interleaved layers'
    pyramid pass, the tiny pyramid levels a [[paths]] entry declares;
  - a user's package is held to its own declaration: its stages, and a
    [[paths]] entry that no matrix reaches until a group does;
  - a bad --matrix or [[paths]] entry exits 2 with one line naming it.

    test_coverage.py SOURCE_DIR BUILD_DIR
"""
import json
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_packages  # noqa: E402  (the ring_ao test package)

failures = 0


def check(ok, what, out=None):
    global failures
    if not ok:
        failures += 1
        print(f"FAIL {what}" + (f"\n{out.stdout}{out.stderr}" if out else ""))


def coverage(cavity, *args, env=None):
    return test_packages.run([cavity, *args], env=env)


def without(matrices, matrix, test):
    """matrices.json with the groups of `matrix` for which test(group) holds taken out."""
    m = json.loads(json.dumps(matrices))
    m[matrix]["groups"] = [g for g in m[matrix]["groups"] if not test(g)]
    return m


def main():
    source, build = sys.argv[1], sys.argv[2]
    cavity = os.path.join(build, "harness", "cavity")
    matrices = json.load(open(os.path.join(source, "baselines", "matrices.json")))

    r = coverage(cavity, "kernels", "coverage", "--matrix", "ci,gpu-cpu")
    check(r.returncode == 0 and re.match(r"cavity kernels coverage: all \d+ paths of \d+ kernels", r.stdout),
          "the stored matrices reach every path", r)

    tmp = tempfile.mkdtemp(prefix="cavity-coverage-")
    try:
        base = os.path.join(tmp, "baselines")
        os.makedirs(base)
        cases = [
            ("the interleaved layers", lambda g: "interleave" in g.get("params", {}),
             ["depth_pyramid_layered:compute/gl", "depth_pyramid_layered:compute/vk"]),
            ("a tiny image", lambda g: g["sizes"] == ["24x12"],
             ["alchemy_fast:tiny_levels (lt(min(width, height), 16))", "hemisphere_fast:tiny_levels",
              "ssdo_fast:tiny_levels"]),
            ("exact positions", lambda g: "exact" in g.get("params", {}),
             ["alchemy_fast:exact=1", "hemisphere_fast:exact=1"]),
        ]
        for what, test, named in cases:
            json.dump(without(matrices, "gpu-cpu", test), open(os.path.join(base, "matrices.json"), "w"))
            r = coverage(cavity, "kernels", "coverage", "--baselines", base, "--matrix", "ci,gpu-cpu")
            lines = r.stderr.splitlines()
            check(r.returncode == 1 and len(lines) == 1 and all(n in r.stderr for n in named) and r.stdout == "",
                  f"without {what}: exit 1, one line naming {named}", r)

        # A user's package: gpu-cpu's "all" runs it at its defaults, on
        # every stage, but its own [[paths]] entry needs a wider ring.
        pkg = os.path.join(tmp, "packages", "ring_ao")
        toml = test_packages.TOML + '\n[[paths]]\nname = "wide_ring"\nwhen = "gt(ring_px, 16)"\n'
        test_packages.make(pkg, toml=toml)
        env = dict(os.environ, CAVITY_KERNELS=os.path.dirname(pkg))
        mine = dict(matrices)
        group = {"scenes": ["corner"], "kernels": ["ring_ao"], "samples": [8], "blurs": [4], "resolutions": ["full"],
                 "sizes": ["160x90"], "apis": ["gl", "vk"], "stages": ["compute", "fragment"]}
        mine["mine"] = {"description": "the test package", "groups": [group]}
        json.dump(mine, open(os.path.join(base, "matrices.json"), "w"))
        r = coverage(cavity, "kernels", "coverage", "--baselines", base, "--matrix", "ci", env=env)
        check(r.returncode == 1 and "ring_ao:compute/gl" in r.stderr and "ring_ao:fragment/vk" not in r.stderr,
              "ci runs the package on the fragment stage alone (its \"all\" group): the compute stage is a hole", r)
        r = coverage(cavity, "kernels", "coverage", "--baselines", base, "--matrix", "ci,gpu-cpu,mine", env=env)
        check(r.returncode == 1 and "1 of" in r.stderr and "ring_ao:wide_ring (gt(ring_px, 16))" in r.stderr,
              "the stored matrices and the package's own: only its declared path is left", r)
        group["params"] = {"ring_px": [24]}
        json.dump(mine, open(os.path.join(base, "matrices.json"), "w"))
        r = coverage(cavity, "kernels", "coverage", "--baselines", base, "--matrix", "ci,gpu-cpu,mine", env=env)
        check(r.returncode == 0, "the package's matrix with a wide ring: every path reached", r)
        # A package's own baselines, with the package's matrix alone: --kernel
        # counts its paths, not the built-ins' that matrix never runs.
        json.dump({"mine": mine["mine"]}, open(os.path.join(base, "matrices.json"), "w"))
        r = coverage(cavity, "kernels", "coverage", "--baselines", base, "--kernel", "ring_ao", env=env)
        check(r.returncode == 0 and re.match(r"cavity kernels coverage: all \d+ paths of 1 kernels", r.stdout),
              "--kernel ring_ao over the package's matrix: its paths alone", r)
        r = coverage(cavity, "kernels", "coverage", "--baselines", base, env=env)
        check(r.returncode == 1 and "alchemy:" in r.stderr, "without --kernel the built-ins count, and are holes", r)
        json.dump(mine, open(os.path.join(base, "matrices.json"), "w"))

        # Bad input: one line, exit 2.
        r = coverage(cavity, "kernels", "coverage", "--matrix", "ci,nope")
        check(r.returncode == 2 and len(r.stderr.splitlines()) == 1 and "--matrix nope" in r.stderr,
              "an unknown matrix: exit 2 naming it", r)
        r = coverage(cavity, "kernels", "coverage", "--matrix", "ci,,gpu-cpu")
        check(r.returncode == 2 and "empty item" in r.stderr and "--matrix" in r.stderr, "an empty matrix name: exit 2", r)
        shutil.rmtree(pkg)
        test_packages.make(pkg, toml=test_packages.TOML + '\n[[paths]]\nname = "x"\nwhen = "gt(rings, 2)"\n')
        r = coverage(cavity, "kernels", "coverage", env=env)
        check(r.returncode == 2 and len(r.stderr.splitlines()) == 1 and re.search(r"kernel\.toml:\d+: paths\[0\]\.when", r.stderr),
              "a [[paths]] condition naming an unknown parameter: exit 2 naming the key", r)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"coverage: {failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
