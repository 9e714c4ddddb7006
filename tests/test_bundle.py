#!/usr/bin/env python3
"""The GPU machine's bundle as that machine uses it (docs/gpu.md):
scripts/bundle.sh packs cavity_bench xz-compressed, and the wrappers unpack
it on first use, also when several start at once; a damaged archive is an
error that names it, not a half-written program.

    test_bundle.py SOURCE_DIR BUILD_DIR
"""
import os
import shutil
import subprocess
import sys
import tempfile


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def main():
    source, build = (os.path.abspath(p) for p in sys.argv[1:3])
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "bundle")
        # A kernel package travels in the bundle and its kernel is in the sweep there.
        pkg = os.path.join(tmp, "pkgs")
        shutil.copytree(os.path.join(source, "kernels", "ao", "gtao"), os.path.join(pkg, "gtao_copy"))
        toml = os.path.join(pkg, "gtao_copy", "kernel.toml")
        text = open(toml).read().replace('name = "gtao"', 'name = "gtao_copy"')
        text = text.replace('name = "slices"', 'name = "copy_slices"').replace('name = "multibounce"', 'name = "copy_bounce"')
        open(toml, "w").write(text)
        glsl = os.path.join(pkg, "gtao_copy", "gtao.glsl")
        # Read before the write opens (and empties) the file.
        code = open(glsl).read().replace("P.slices", "P.copy_slices").replace("P.multibounce", "P.copy_bounce")
        open(glsl, "w").write(code)
        # xz's fastest preset: what is checked is the packing, not its ratio.
        env = dict(os.environ, BUNDLE_BINARIES="cavity_bench", BUILD_DIR=build, BUNDLE_KERNELS=pkg, BUNDLE_XZ="1")
        packed = run([os.path.join(source, "scripts", "bundle.sh"), out], env=env)
        assert packed.returncode == 0, packed.stderr
        names = os.listdir(out)
        assert "cavity_bench.xz" in names and "cavity_bench" not in names, names

        # Three wrappers at once: each unpacks (or finds it unpacked) and runs.
        procs = [subprocess.Popen([os.path.join(out, "run.sh"), "--benchmark_list_tests"],
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(3)]
        for p in procs:
            stdout, stderr = p.communicate(timeout=300)
            assert p.returncode == 0, stderr
            assert "/compute/" in stdout, stdout[:500]
            assert "/gtao_copy/" in stdout, "the bundle's kernel package is not in the sweep"
        names = os.listdir(out)
        assert "cavity_bench" in names and not any(n.endswith(".xz") or ".unpack." in n for n in names), names
        assert os.access(os.path.join(out, "cavity_bench"), os.X_OK)

        # A damaged archive: a one-line error naming it, exit 1, and no program left behind.
        os.remove(os.path.join(out, "cavity_bench"))
        with open(os.path.join(out, "cavity_bench.xz"), "wb") as f:
            f.write(b"not xz at all")
        bad = run([os.path.join(out, "run.sh"), "--help"])
        assert bad.returncode == 1, (bad.returncode, bad.stderr)
        assert "cavity_bench.xz" in bad.stderr and "xz cannot decompress" in bad.stderr, bad.stderr
        assert "cavity_bench" not in os.listdir(out) and not any(".unpack." in n for n in os.listdir(out))
    print("bundle: packed, unpacked by three wrappers at once, a damaged archive refused")


if __name__ == "__main__":
    main()
