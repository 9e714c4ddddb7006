#!/usr/bin/env python3
"""Kernel packages as a user makes them (docs/packages.md): a folder made
here with a kernel.toml and its GLSL, no rebuild of Cavity.

  - `cavity kernels check` passes it on both APIs and stages and names the
    flag it adds; one whose declaration disagrees with the shader's uniform
    block (a declared parameter the shader never reads) fails with a line
    naming the declaration and the parameter;
  - it runs through `cavity run` (both APIs), `cavity gate` (approved by
    digest, then passing by digest), `cavity quality` and `cavity_bench`,
    with configuration ids of the built-ins' form;
  - each of the bad packages below exits 2 with one line that names the
    file (and for a declaration error its line and key), and writes nothing.

    test_packages.py SOURCE_DIR BUILD_DIR
"""
import json
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

GLSL = """// A test package: Alchemy-like obscurance on a ring of samples.
#include "include/common.glsl"
#include "ring.glsl"

void cavity_main(ivec2 pixel) {
    vec4 centre = texelFetch(in_position, pixel, 0);
    if (isBackground(centre.w)) {
        write_ao(pixel, vec4(1.0));
        return;
    }
    vec3 N = texelFetch(in_normal, pixel, 0).xyz;
    float occlusion = 0.0;
    for (int i = 0; i < P.samples; ++i) {
        ivec2 s = pixel + ringOffset(i, P.samples, P.ring_px);
        if (!inImage(s)) continue;
        vec4 S = texelFetch(in_position, s, 0);
        if (isBackground(S.w)) continue;
        vec3 d = S.xyz - centre.xyz;
        if (lengthSquared(d) > P.radius * P.radius) continue;
        occlusion += max(0.0, dot(N, normalize(d)));
    }
    write_ao(pixel, vec4(1.0 - occlusion / float(P.samples), 0.0, 0.0, 0.0));
}
"""

RING = """// The package's own include, beside its kernel.
ivec2 ringOffset(int i, int n, int radius) {
    vec2 cs = cosSinTurns((float(i) + 0.5) / float(n));
    return ivec2(round(cs * float(radius)));
}
"""

TOML = """name = "ring_ao"
summary = "a test package: obscurance from a ring of samples"
role = "ao"
file = "ring_ao.glsl"

[[params]]
name = "samples"
default = 8

[[params]]
name = "radius"

[[params]]
name = "ring_px"
type = "int"
default = 4
min = 1
max = 32
unit = "px"
help = "the ring's radius in pixels"

[[inputs]]
name = "position"

[[inputs]]
name = "normal"

[[outputs]]
name = "ao"
format = "R16F"

[cost]
fetches = "2 + samples"
bytes = "RGBA32F + RGBA16F + samples * RGBA32F + R16F"
fetch_slots = "slots(RGBA32F) + slots(RGBA16F) + samples * slots(RGBA32F)"
dram_bytes = "RGBA32F + RGBA16F + R16F"
"""


def sub(text, old, new):
    assert old in text, old
    return text.replace(old, new, 1)


# (what, edit of the package folder, expected: a regex the one line must match)
def bad_packages():
    t = TOML
    cases = [
        ("no kernel.toml", lambda d: os.remove(f"{d}/kernel.toml"), r"no kernel\.toml"),
        ("not TOML", lambda d: w(d, "kernel.toml", t + "\n[cost\n"), r"kernel\.toml:\d+: not TOML"),
        ("unknown key", lambda d: w(d, "kernel.toml", "colour = 1\n" + t), r"kernel\.toml:1: colour = 1: unknown key"),
        ("no name", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_ao"\n', "")), r"kernel\.toml:1: name: missing"),
        ("bad name", lambda d: w(d, "kernel.toml", sub(t, '"ring_ao"', '"Ring-AO"')), r":1: name = Ring-AO: must be a-z"),
        ("built-in's name", lambda d: w(d, "kernel.toml", sub(t, '"ring_ao"', '"alchemy"')), r":1: name = alchemy: is taken"),
        ("no summary", lambda d: w(d, "kernel.toml", re.sub(r"summary = .*\n", "", t)), r"summary: missing"),
        ("role", lambda d: w(d, "kernel.toml", sub(t, 'role = "ao"', 'role = "blur"')), r":3: role = blur: must be ao"),
        ("missing GLSL file", lambda d: os.remove(f"{d}/ring_ao.glsl"), r":4: file = ring_ao\.glsl: no such file"),
        ("file outside", lambda d: w(d, "kernel.toml", sub(t, '"ring_ao.glsl"', '"../x.glsl"')),
         r"file = \.\./x\.glsl: must name a file in the package's folder by its own name"),
        ("file is not GLSL", lambda d: w(d, "kernel.toml", sub(t, '"ring_ao.glsl"', '"kernel.toml"')),
         r"file = kernel\.toml: must name the kernel's GLSL source"),
        ("file through a link out", lambda d: (os.rename(f"{d}/ring_ao.glsl", f"{d}/../ring_ao_outside.glsl"),
                                               os.symlink(os.path.abspath(f"{d}/../ring_ao_outside.glsl"), f"{d}/ring_ao.glsl")),
         r"file = ring_ao\.glsl: no such file .*a link out of the folder"),
        ("duplicate parameter", lambda d: w(d, "kernel.toml", t + '\n[[params]]\nname = "radius"\n'),
         r"params\[3\]\.name = radius: declared twice"),
        ("default out of range", lambda d: w(d, "kernel.toml", sub(t, "default = 4", "default = 40")),
         r"params\[2\]\.default = 40: outside the parameter's range: must be an integer in 1\.\.32"),
        ("min over max", lambda d: w(d, "kernel.toml", sub(t, "min = 1\nmax = 32", "min = 9\nmax = 3")),
         r"params\[2\]\.max = 3: must be at least min"),
        ("new parameter without type", lambda d: w(d, "kernel.toml", sub(t, 'type = "int"\n', "")),
         r"params\[2\]\.name = ring_px: no parameter of that name; a new one needs its type"),
        ("misspelt harness parameter", lambda d: w(d, "kernel.toml", sub(t, 'name = "radius"\n', 'name = "radious"\n')),
         r"params\[1\]\.name = radious: no parameter of that name \(did you mean radius\?\)"),
        # Another type is said at its type, before any key the new type lacks.
        ("harness parameter retyped", lambda d: w(d, "kernel.toml", sub(t, 'name = "radius"\n', 'name = "radius"\ntype = "int"\n')),
         r"params\[1\]\.type = \"int\": 'radius' is declared already"),
        ("harness parameter declared otherwise", lambda d: w(d, "kernel.toml", sub(t, 'name = "radius"\n', 'name = "radius"\ntype = "int"\nmin = 1\nmax = 9\nhelp = "h"\n')),
         r"params\[1\]\.type = \"int\": 'radius' is declared already, as a number > 0"),
        # The same type, another range: said at the key that differs.
        ("harness parameter's range redeclared", lambda d: w(d, "kernel.toml", sub(t, 'name = "samples"\n', 'name = "samples"\ntype = "int"\nmin = 1\nmax = 64\nunit = "samples"\nhelp = "h"\n')),
         r"params\[0\]\.max = 64: 'samples' is declared already, as an integer in 1\.\.256"),
        ("duplicate enum choice", lambda d: w(d, "kernel.toml", sub(sub(t, 'type = "int"', 'type = "enum"\nchoices = ["near", "near"]'), "default = 4\nmin = 1\nmax = 32\n", 'default = "near"\n')),
         r"params\[2\]\.choices = \"near\": each choice must be a distinct name"),
        # A choice is one segment of a configuration id, a path under --out.
        ("choice with a slash", lambda d: w(d, "kernel.toml", sub(sub(t, 'type = "int"', 'type = "enum"\nchoices = ["near", "x/../../up"]'), "default = 4\nmin = 1\nmax = 32\n", 'default = "near"\n')),
         r"params\[2\]\.choices = \"x/\.\./\.\./up\": each choice must be a distinct name of letters"),
        # A parameter named like a flag of the commands aborted inside CLI11;
        # a GLSL word failed only at compile time, naming neither file nor key.
        ("parameter named like a flag", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_px"', 'name = "frames"')),
         r"params\[2\]\.name = frames: is reserved"),
        ("parameter named like a GLSL word", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_px"', 'name = "uniform"')),
         r"params\[2\]\.name = uniform: is reserved"),
        # Compute shaders' word and a matrix shape: they broke the generated code.
        ("parameter named like a compute word", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_px"', 'name = "shared"')),
         r"params\[2\]\.name = shared: is reserved"),
        ("parameter named like a matrix shape", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_px"', 'name = "mat3x2"')),
         r"params\[2\]\.name = mat3x2: is reserved"),
        # A word of the cost and paths formulas: shadowed in one, read in the other.
        ("parameter named like a formula word", lambda d: w(d, "kernel.toml", sub(t, 'name = "ring_px"', 'name = "width"')),
         r"params\[2\]\.name = width: is reserved"),
        ("interleaved without its parameter and input", lambda d: w(d, "kernel.toml", sub(t, 'role = "ao"', 'role = "ao"\ninterleaved = true')),
         r"interleaved = true: needs the interleave parameter and a zlayers input"),
        ("array named like a parameter", lambda d: w(d, "kernel.toml", t + '\n[[arrays]]\nname = "ring_px"\nvec4 = 4\nderive = "spiral"\n'),
         r"arrays\[0\]\.name = ring_px: is taken by a parameter"),
        ("int default given as a bool", lambda d: w(d, "kernel.toml", sub(t, "default = 4", "default = true")),
         r"params\[2\]\.default = true: must be a number"),
        ("int default past 64 bits of a double", lambda d: w(d, "kernel.toml", sub(t, "default = 4", "default = 9223372036854775807")),
         r"params\[2\]\.default = 9223372036854775807: outside the parameter's range: must be an integer in 1\.\.32"),
        ("choices on an int", lambda d: w(d, "kernel.toml", sub(t, "min = 1\n", 'min = 1\nchoices = ["a"]\n')),
         r"params\[2\]\.choices = \[1 values\]: does not apply to a parameter of type int"),
        ("a line break in the summary", lambda d: w(d, "kernel.toml", re.sub(r"summary = .*\n", lambda m: 'summary = "one\\ntwo"\n', t)),
         r'summary = "one\\x0atwo": must be one line of printable text'),
        ("an empty optional string", lambda d: w(d, "kernel.toml", sub(t, 'unit = "px"', 'unit = ""')),
         r"params\[2\]\.unit = \"\": must not be empty \(leave the key out\)"),
        ("cost infinite where the kernel runs", lambda d: w(d, "kernel.toml", sub(t, '"2 + samples"', '"2 + samples / max(ring_px - 3, 0)"')),
         r"cost\.fetches = \"2 \+ samples / max\(ring_px - 3, 0\)\": gives inf at ring_px = 1: a count per pixel must be finite"),
        ("cost nested past the stack", lambda d: w(d, "kernel.toml", sub(t, '"2 + samples"', '"' + "(" * 5000 + "1" + ")" * 5000 + '"')),
         r"cost\.fetches = .*\(10003 characters\): column 65: nested more than 64 deep"),
        ("expectation NaN", lambda d: w(d, "kernel.toml", t + "\n[expectations]\nopen_mean = nan\n"),
         r"expectations\.open_mean = nan: must be a number in 0\.\.1"),
        ("int range past 32 bits", lambda d: w(d, "kernel.toml", sub(t, "max = 32", "max = 4294967296")),
         r"params\[2\]\.max = 4294967296: outside what a 32-bit int holds"),
        ("float range past 32 bits", lambda d: w(d, "kernel.toml", sub(sub(t, 'type = "int"', 'type = "float"'), "max = 32", "max = 1e39")),
         r"params\[2\]\.max = [0-9.e+]+: outside what a 32-bit float holds"),
        ("min not a number", lambda d: w(d, "kernel.toml", sub(sub(t, 'type = "int"', 'type = "float"'), "min = 1", "min = nan")),
         r"params\[2\]\.min = nan: must be a finite number"),
        ("empty help", lambda d: w(d, "kernel.toml", sub(t, 'help = "the ring\'s radius in pixels"', 'help = ""')),
         r"params\[2\]\.help = \"\": must not be empty"),
        ("enum default not a choice", lambda d: w(d, "kernel.toml", sub(sub(t, 'type = "int"', 'type = "enum"\nchoices = ["near", "far"]'), "default = 4\nmin = 1\nmax = 32\n", 'default = "farr"\n')),
         r"params\[2\]\.default = farr: must be one of near, far"),
        ("unknown type", lambda d: w(d, "kernel.toml", sub(t, 'type = "int"', 'type = "double"')),
         r"params\[2\]\.type = double: must be int, float, bool or enum"),
        ("harness parameter's range", lambda d: w(d, "kernel.toml", sub(t, 'name = "radius"\n', 'name = "radius"\nmax = 2\n')),
         r"params\[1\]\.max = 2: 'radius' is declared already"),
        ("float compiled in", lambda d: w(d, "kernel.toml", sub(t, 'name = "radius"\n', 'name = "radius"\ncompiled_in = true\n')),
         r"params\[1\]\.compiled_in = true: only an int, bool or enum"),
        ("input no pass provides", lambda d: w(d, "kernel.toml", sub(t, 'name = "normal"', 'name = "velocity"')),
         r"inputs\[1\]\.name = velocity: no pass provides it"),
        ("input read twice", lambda d: w(d, "kernel.toml", sub(t, 'name = "normal"', 'name = "position"')),
         r"inputs\[1\]\.name = position: read twice"),
        ("no inputs", lambda d: w(d, "kernel.toml", re.sub(r"\[\[inputs\]\]\nname = \"\w+\"\n\n", "", t)), r"inputs: missing"),
        ("output format", lambda d: w(d, "kernel.toml", sub(t, 'format = "R16F"', 'format = "RGB10A2"')),
         r"outputs\[0\]\.format = RGB10A2: no backend image of that format"),
        ("output name", lambda d: w(d, "kernel.toml", sub(t, 'name = "ao"', 'name = "occlusion"')),
         r"outputs\[0\]\.name = occlusion: an AO kernel writes ao"),
        ("cost syntax", lambda d: w(d, "kernel.toml", sub(t, '"2 + samples"', '"2 + * samples"')),
         r"cost\.fetches = \"2 \+ \* samples\": column 5"),
        ("cost unknown name", lambda d: w(d, "kernel.toml", sub(t, '"2 + samples"', '"2 + taps"')),
         r"cost\.fetches = \"2 \+ taps\": .*'taps' is neither a parameter"),
        ("cost missing key", lambda d: w(d, "kernel.toml", re.sub(r"dram_bytes = .*\n", "", t)), r"cost\.dram_bytes: missing"),
        ("array generator", lambda d: w(d, "kernel.toml", t + '\n[[arrays]]\nname = "taps"\nvec4 = 4\nderive = "sobol"\n'),
         r"arrays\[0\]\.derive = sobol: must be gaussian_weights"),
        ("pipeline blur", lambda d: w(d, "kernel.toml", t + '\n[pipeline]\nblur = "separable"\n'),
         r"pipeline\.blur = separable: this kernel gets the bilateral blur"),
        ("workgroup", lambda d: w(d, "kernel.toml", 'workgroup = [16, 3]\n' + t), r":1: workgroup = \[16, 3\]: must be"),
    ]
    return cases


def w(folder, name, text):
    with open(os.path.join(folder, name), "w") as f:
        f.write(text)


def make(folder, toml=TOML, glsl=GLSL):
    os.makedirs(folder, exist_ok=True)
    w(folder, "kernel.toml", toml)
    w(folder, "ring_ao.glsl", glsl)
    w(folder, "ring.glsl", RING)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600, **kw)


def check_bad(cavity, root):
    failures = 0
    for what, edit, pattern in bad_packages():
        pkg = os.path.join(root, "bad", what.replace(" ", "_").replace("'", ""))
        make(pkg)
        edit(pkg)
        out = os.path.join(root, "bad_out")
        r = run([cavity, "run", "--kernels", pkg, "--kernel", "ring_ao", "--res", "32x18", "--frames", "1",
                 "--out", out])
        lines = r.stderr.strip().splitlines()
        ok = (r.returncode == 2 and len(lines) == 1 and re.search(pattern, lines[0]) and not os.path.exists(out)
              and r.stdout == "")
        if not ok:
            failures += 1
            print(f"FAIL bad package '{what}': exit {r.returncode}, stderr {r.stderr!r}, expected /{pattern}/")
    # A GLSL error names the package's file and line, not the assembled source.
    pkg = os.path.join(root, "bad", "glsl_error")
    make(pkg, glsl=GLSL.replace("float occlusion = 0.0;", "float occlusion = undeclared_thing;"))
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 2 or not re.search(re.escape(os.path.join(pkg, "ring_ao.glsl")) + r":12: .*undeclared_thing",
                                          r.stderr):
        failures += 1
        print(f"FAIL a GLSL error: exit {r.returncode}, {r.stderr!r}")
    # An #include that is not there is said where it is written, once (not
    # once for each API and stage, naming neither includer nor line).
    pkg = os.path.join(root, "bad", "include_missing")
    make(pkg, glsl='#include "nope.glsl"\n' + GLSL)
    r = run([cavity, "kernels", "check", pkg])
    said = [l for l in r.stderr.splitlines() if "nope.glsl" in l]
    if r.returncode != 2 or len(said) != 1 or not re.search(
            re.escape(os.path.join(pkg, "ring_ao.glsl")) + r':1: #include "nope\.glsl": no such file beside it', said[0]):
        failures += 1
        print(f"FAIL a missing #include: exit {r.returncode}, {r.stderr!r}")
    # An #include out of the package's folder, of a file that is there: said
    # as not followed (it read "no such file", sending its author looking).
    pkg = os.path.join(root, "bad", "include_outward")
    make(pkg, glsl='#include "../outside.glsl"\n' + GLSL)
    with open(os.path.join(root, "bad", "outside.glsl"), "w") as f:
        f.write("float outside() { return 1.0; }\n")
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 2 or '#include "../outside.glsl": a path out of the folder' not in r.stderr:
        failures += 1
        print(f"FAIL an #include out of the folder: exit {r.returncode}, {r.stderr!r}")
    # A package inside a package: refused, not read as the outer one's files.
    pkg = os.path.join(root, "bad", "nested")
    make(pkg)
    make(os.path.join(pkg, "inner"), toml=TOML.replace('"ring_ao"', '"ring_inner"'))
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 2 or "inner/kernel.toml: a package inside the package" not in r.stderr:
        failures += 1
        print(f"FAIL a nested package: exit {r.returncode}, {r.stderr!r}")
    # A shader that compiles on one API only: gl_VertexIndex is Vulkan's word.
    pkg = os.path.join(root, "bad", "one_api")
    make(pkg, glsl=GLSL.replace("float occlusion = 0.0;", "float occlusion = 0.0 * float(gl_VertexIndex);"))
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 2 or ("(gl)" not in r.stderr and "gl compute" not in r.stderr):
        failures += 1
        print(f"FAIL a shader for one API only: exit {r.returncode}, {r.stderr!r}")
    # Run with the GLSL error: exit 2 on either API (glslang rejects the
    # user's source on GL too, before the driver's compiler is asked).
    make(os.path.join(root, "compile_error", "ring_ao"),
         glsl=GLSL.replace("float occlusion = 0.0;", "float occlusion = undeclared_thing;"))
    for api in ("gl", "vk"):
        r = run([cavity, "run", "--kernels", os.path.join(root, "compile_error"), "--kernel", "ring_ao", "--backend", api,
                 "--res", "32x18", "--frames", "1", "--warmup", "0", "--quiet",
                 "--out", os.path.join(root, "glsl_error_" + api)])
        if r.returncode != 2 or "undeclared_thing" not in r.stderr:
            failures += 1
            print(f"FAIL run of a kernel that does not compile on {api}: exit {r.returncode}, {r.stderr!r}")
    # A gate whose configuration did not compile has no image to accept:
    # `baselines update` of it says so, exit 2, and writes nothing.
    base = os.path.join(root, "compile_error_baselines")
    os.makedirs(base)
    for f in ("manifest.json", "budgets.json"):
        shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "baselines", f), base)
    json.dump({"mine": {"description": "d", "groups": [
        {"scenes": ["corner"], "kernels": ["ring_ao"], "samples": [8], "blurs": [4], "resolutions": ["full"],
         "sizes": ["64x36"], "apis": ["vk"], "stages": ["compute"]}]}}, open(os.path.join(base, "matrices.json"), "w"))
    kernels = os.path.join(root, "compile_error")
    run([cavity, "gate", "--kernels", kernels, "--matrix", "mine", "--baselines", base, "--quiet", "--retries", "0",
         "--out", os.path.join(root, "compile_error_gate")])
    before = sorted(os.listdir(base))
    # With a filter, and without one (every failure; the summary offers no
    # accept command then).
    for chosen in (["--filter", "ring_ao"], []):
        r = run([cavity, "baselines", "update", "--kernels", kernels, "--from", os.path.join(root, "compile_error_gate"),
                 "--baselines", base, *chosen])
        if r.returncode != 2 or "1 selected configurations rendered no image" not in r.stderr or sorted(os.listdir(base)) != before:
            failures += 1
            print(f"FAIL baselines update {chosen} of a configuration that did not compile: exit {r.returncode}, {r.stderr!r}")
    with open(os.path.join(root, "compile_error_gate", "summary.md")) as f:
        if "baselines update" in f.read():
            failures += 1
            print("FAIL the summary of a gate that rendered no image offers to accept one")
    # ... nor is an edit that did not compile copied over the package's
    # file by --with-kernel-source (it would replace the working one).
    good = os.path.join(root, "copy_guard")
    make(os.path.join(good, "ring_ao"))
    broken = os.path.join(root, "broken_edit.glsl")
    with open(broken, "w") as f:
        f.write(GLSL.replace("float occlusion = 0.0;", "float occlusion = undeclared_thing;"))
    run([cavity, "gate", "--kernels", good, "--matrix", "mine", "--baselines", base, "--quiet", "--retries", "0",
         "--kernel-source", "ring_ao.glsl=" + broken, "--out", os.path.join(root, "copy_guard_gate")])
    original = open(os.path.join(good, "ring_ao", "ring_ao.glsl")).read()
    r = run([cavity, "baselines", "update", "--kernels", good, "--from", os.path.join(root, "copy_guard_gate"),
             "--baselines", base, "--with-kernel-source"])
    if (r.returncode != 2 or "did not render with the edit" not in r.stderr
            or open(os.path.join(good, "ring_ao", "ring_ao.glsl")).read() != original):
        failures += 1
        print(f"FAIL --with-kernel-source of an edit that did not compile: exit {r.returncode}, {r.stderr!r}")
    n = len(bad_packages()) + 7
    print(f"bad packages: {n - failures} of {n} refused with one line naming the file")
    return failures


def check_flag_names(cavity, bench, render, root):
    """Every one-word flag of the commands that take kernel parameters is a
    name a package's new parameter cannot take: reserved, or a parameter
    the harness declares already (a clash aborted inside CLI11)."""
    failures = 0
    names = set()
    for cmd in ([cavity, "run"], [cavity, "gate"], [cavity, "quality"], [bench], [render]):
        names |= set(re.findall(r"--([a-z][a-z0-9_]*)\b(?!-)", run(cmd + ["--help"]).stdout))
    for name in sorted(names):
        pkg = os.path.join(root, "flag_names", name, "ring_ao")
        make(pkg, toml=TOML.replace('name = "ring_px"', f'name = "{name}"').replace('unit = "px"', 'unit = "test units"'),
             glsl=GLSL.replace("P.ring_px", f"P.{name}"))
        r = run([cavity, "kernels", "check", pkg])
        said = any(w in r.stderr for w in (f"name = {name}: is reserved", f"'{name}' is declared already",
                                           f"name = {name}: declared twice"))
        if r.returncode != 2 or len(r.stderr.strip().splitlines()) != 1 or not said:
            failures += 1
            print(f"FAIL a parameter named --{name}: exit {r.returncode}, {r.stderr!r}")
    print(f"flag names: {len(names) - failures} of {len(names)} refused as a new parameter's name")
    return failures


def check_builtins_and_outputs(cavity, root, source):
    """Every built-in package passes check as a user would run it on the
    checkout's folders of them (compiled-in values, switches the harness
    reads, tables derived on the CPU, compute-only mip chains), each package
    named in the output; a copy of kernels/ with a package the build never
    embedded fails naming it; an output no write reaches fails."""
    failures = 0
    for group in ("ao", "passes"):
        folder = os.path.join(source, "kernels", group)
        names = sorted(n for n in os.listdir(folder) if os.path.isfile(os.path.join(folder, n, "kernel.toml")))
        r = run([cavity, "kernels", "check", folder])
        passed = set(re.findall(r"^(\w+) \(kernels/" + group + r"/\w+/kernel\.toml\): compiles on vk and gl", r.stdout, re.M))
        if r.returncode != 0 or passed != set(names):
            failures += 1
            print(f"FAIL check of the built-in packages in kernels/{group}: exit {r.returncode}, "
                  f"not passed: {sorted(set(names) - passed)}; {r.stderr.strip()[:400]!r}")
    copy = os.path.join(root, "checkout", "kernels")
    shutil.copytree(os.path.join(source, "kernels"), copy)
    make(os.path.join(copy, "ao", "ring_ao"))
    r = run([cavity, "kernels", "check", os.path.join(copy, "ao")])
    line = [l for l in r.stderr.splitlines() if "ring_ao" in l]
    if r.returncode != 2 or not line or "has not embedded" not in line[0] or "alchemy (" not in r.stdout:
        failures += 1
        print(f"FAIL check of a folder of built-in packages with one the build never embedded: {r.returncode} "
              f"{r.stderr.strip()[:400]!r}")
    pkg = os.path.join(root, "unwritten")
    make(pkg, glsl=GLSL.replace("write_ao(pixel, ", "keep_ao(").replace("void cavity_main", "void keep_ao(vec4 v) {}\nvoid cavity_main", 1))
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 2 or "never calls write_ao" not in r.stderr:
        failures += 1
        print(f"FAIL check of a package that never writes its output: {r.returncode} {r.stderr!r}")
    return failures


def check_disagreement(cavity, root):
    """A declared parameter the shader never reads: check names it, also
    when its folder of packages is loaded already (CAVITY_KERNELS, as
    kernels.md suggests), where check once checked nothing and exited 0."""
    failures = 0
    pkg = os.path.join(root, "unread", "ring_ao")
    make(pkg, toml=TOML + '\n[[params]]\nname = "bias"\n')
    for target, env in ((pkg, None), (os.path.dirname(pkg), dict(os.environ, CAVITY_KERNELS=os.path.dirname(pkg)))):
        r = run([cavity, "kernels", "check", target], env=env)
        line = [l for l in r.stderr.splitlines() if "bias" in l]
        if not (r.returncode == 2 and line and "kernel.toml" in line[0] and "never reads P.bias" in line[0]):
            failures += 1
            print(f"FAIL check {target} (CAVITY_KERNELS {env and env['CAVITY_KERNELS']}) did not catch a declared "
                  f"parameter the shader never reads: {r.returncode} {r.stderr!r}")
    return failures


def check_unknown_reference(cavity, root):
    """A reference line naming no registered CPU reference: check names it.
    A built-in's name, left in a copy of its package, is not the copy's:
    check says it has none (it once read "CPU reference: yes")."""
    failures = 0
    pkg = os.path.join(root, "unknown_reference", "ring_ao")
    make(pkg, toml=TOML.replace('file = "ring_ao.glsl"', 'file = "ring_ao.glsl"\nreference = "my_ao"', 1))
    r = run([cavity, "kernels", "check", pkg])
    line = [l for l in r.stderr.splitlines() if "reference = my_ao" in l]
    if not (r.returncode == 2 and line and "kernel.toml" in line[0] and "no CPU reference of that name" in line[0]):
        failures += 1
        print(f"FAIL check did not catch an unknown reference name: {r.returncode} {r.stderr!r}")
    pkg = os.path.join(root, "borrowed_reference", "ring_ao")
    make(pkg, toml=TOML.replace('file = "ring_ao.glsl"', 'file = "ring_ao.glsl"\nreference = "alchemy"', 1))
    r = run([cavity, "kernels", "check", pkg])
    if r.returncode != 0 or "CPU reference: none" not in r.stdout:
        failures += 1
        print(f"FAIL a package with a built-in's reference line: {r.returncode} {r.stdout!r} {r.stderr!r}")
    return failures


def main():
    source, build = (os.path.abspath(p) for p in sys.argv[1:3])
    cavity = os.path.join(build, "harness", "cavity")
    bench = os.path.join(build, "bench", "cavity_bench")
    with tempfile.TemporaryDirectory() as root:
        pkg = os.path.join(root, "kernels", "ring_ao")
        make(pkg)
        failures = 0

        r = run([cavity, "kernels", "check", pkg])
        assert r.returncode == 0, r.stdout + r.stderr
        assert "--ring_px" in r.stdout and "CPU reference: none" in r.stdout, r.stdout
        # A float range given as the largest float's shortest text (it reads
        # back a hair above FLT_MAX) is that float.
        wide = os.path.join(root, "wide", "ring_ao")
        make(wide, toml=sub(sub(TOML, 'type = "int"', 'type = "float"'), "min = 1\nmax = 32",
                            "min = -3.4028235e38\nmax = 3.4028235e38"), glsl=GLSL.replace("P.ring_px", "int(P.ring_px)"))
        r = run([cavity, "kernels", "check", wide])
        assert r.returncode == 0, r.stdout + r.stderr
        # A file named "./ring_ao.glsl", or through a link inside the folder,
        # is the package's own.
        dotted = os.path.join(root, "dotted", "ring_ao")
        make(dotted, toml=sub(TOML, '"ring_ao.glsl"', '"./ring_ao.glsl"'))
        linked = os.path.join(root, "linked", "ring_ao")
        make(linked, toml=sub(TOML, '"ring_ao.glsl"', '"main.glsl"'))
        os.symlink("ring_ao.glsl", os.path.join(linked, "main.glsl"))
        for folder in (dotted, linked):
            r = run([cavity, "kernels", "check", folder])
            assert r.returncode == 0, r.stdout + r.stderr
        # ... named as shell completion writes it, with a trailing slash.
        r = run([cavity, "kernels", "check", pkg + "/"])
        assert r.returncode == 0, r.stdout + r.stderr

        # cavity run on both APIs, found through CAVITY_KERNELS.
        env = dict(os.environ, CAVITY_KERNELS=os.path.dirname(pkg))
        out = os.path.join(root, "run")
        r = run([cavity, "run", "--kernel", "ring_ao", "--ring_px", "3", "--backend", "all", "--res", "64x36",
                 "--frames", "2", "--out", out], env=env)
        assert r.returncode == 0, r.stderr
        results = json.load(open(os.path.join(out, "results.json")))
        # The recorded command runs the same again: the package's folder
        # (given by CAVITY_KERNELS) in it, each word as a shell reads it.
        assert shlex.split(results["command"]) == [
            "cavity", "run", "--kernels", pkg, "--kernel", "ring_ao", "--ring_px", "3", "--backend", "all", "--res",
            "64x36", "--frames", "2", "--out", out], results["command"]
        ids = sorted({c["id"] for c in results["configs"]} if "configs" in results else
                     {c["id"] for c in results.get("runs", [])})
        for api in ("gl", "vk"):
            assert any(re.fullmatch(rf"corner/ring_ao/n8/b4/ring_px=3/full/64x36/{api}/compute", i) for i in ids), ids
        # Which package ran, from where, in which version: every report says it.
        packages = results["kernel_packages"]
        assert [(p["name"], p["folder"]) for p in packages] == [("ring_ao", pkg)], packages
        digest = packages[0]["digest"]

        # The gate: a matrix of the package's kernel; approve, then pass by digest.
        base = os.path.join(root, "baselines")
        os.makedirs(base)
        for f in ("manifest.json", "budgets.json"):
            shutil.copy(os.path.join(source, "baselines", f), base)
        json.dump({"mine": {"description": "ring_ao on corner", "frames": 2, "warmup": 1, "groups": [
            {"scenes": ["corner"], "kernels": ["ring_ao"], "samples": [8], "blurs": [4], "resolutions": ["full", "half"],
             "sizes": ["64x36"], "apis": ["gl", "vk"], "stages": ["compute"]}]}}, open(os.path.join(base, "matrices.json"), "w"))
        gate = [cavity, "gate", "--kernels", pkg, "--matrix", "mine", "--baselines", base, "--quiet"]
        first = run(gate + ["--out", os.path.join(root, "gate1")])
        assert first.returncode != 0, "a gate with neither baselines nor approvals passed"
        r = run([cavity, "baselines", "approve", "--kernels", pkg, "--from", os.path.join(root, "gate1"), "--baselines",
                 base, "--why", "the test package's first references", "--store", os.path.join(root, "store")])
        assert r.returncode == 0, r.stderr
        second = run(gate + ["--out", os.path.join(root, "gate2"), "--store", os.path.join(root, "store")])
        assert second.returncode == 0, second.stdout + second.stderr
        judged = json.dumps(json.load(open(os.path.join(root, "gate2", "gate.json"))))
        assert "ring_ao" in judged and "digest" in judged, judged[:800]
        assert json.loads(judged)["kernel_packages"] == packages, judged[:800]

        # quality against the ground truth, and cavity_bench.
        r = run([cavity, "quality", "--kernels", pkg, "--kernel", "ring_ao", "--samples", "8", "--scene", "corner",
                 "--res", "64x36"])
        assert r.returncode == 0 and re.search(r"corner\s+ring_ao\s+8\s+0\.\d+", r.stdout), r.stdout + r.stderr
        # ... at a value of its own parameter: the row measures it (another MAE).
        r3 = run([cavity, "quality", "--kernels", pkg, "--kernel", "ring_ao", "--samples", "8", "--scene", "corner",
                  "--res", "64x36", "--ring_px", "12", "--out", os.path.join(root, "quality3")])
        mae = lambda out: re.search(r"corner\s+ring_ao\s+8\s+(0\.\d+)", out).group(1)
        assert r3.returncode == 0 and mae(r3.stdout) != mae(r.stdout), r3.stdout + r3.stderr
        # ... and says so: on stdout, and in quality.json with the package.
        assert "set for every kernel that declares it: --ring_px 12" in r3.stdout, r3.stdout
        q = json.load(open(os.path.join(root, "quality3", "quality.json")))
        assert q["switches"] == {"ring_px": 12} and q["kernel_packages"] == packages, q
        r = run([bench, "--kernels", pkg, "--sweep", "cpu", "--benchmark_filter=/ring_ao/", "--benchmark_list_tests"])
        assert r.returncode == 0 and "/ring_ao/" in r.stdout, r.stdout + r.stderr
        one = next(l for l in r.stdout.split() if "/vk/" in l)
        r = run([bench, "--kernels", pkg, "--sweep", "cpu", f"--benchmark_filter=^{re.escape(one)}$", "--max-time", "0.05",
                 "--benchmark_format=json"])
        assert r.returncode == 0 and '"name": "' + one in r.stdout, r.stdout[-2000:] + r.stderr
        assert f"ring_ao={pkg} ({digest})" in json.loads(r.stdout)["context"]["cavity_kernel_packages"], r.stdout[:2000]

        # An edit of the package's own shader through --kernel-source, as of a
        # built-in's: the gate judges the edit (twice the occlusion fails the
        # approvals) and records the replacement.
        edited = os.path.join(root, "ring_ao_edit.glsl")
        w(root, "ring_ao_edit.glsl", GLSL.replace("float occlusion = 0.0;", "float occlusion = 0.25;"))
        third = run(gate + ["--out", os.path.join(root, "gate3"), "--store", os.path.join(root, "store"),
                            "--kernel-source", "ring_ao.glsl=" + edited])
        assert third.returncode == 1, third.stdout + third.stderr
        assert edited in json.dumps(json.load(open(os.path.join(root, "gate3", "gate.json")))["kernel_sources"])

        # The edit's run is not approved by digest alone: kernels/ does not hold it.
        r = run([cavity, "baselines", "approve", "--kernels", pkg, "--from", os.path.join(root, "gate3"), "--baselines",
                 base, "--why", "an edit", "--store", os.path.join(root, "store")])
        assert r.returncode == 2 and "--with-kernel-source" in r.stderr, r.stderr
        # The names the reports print select the file too: its path on disk.
        r = run([cavity, "run", "--kernels", pkg, "--kernel", "ring_ao", "--kernel-source",
                 os.path.join(pkg, "ring_ao.glsl") + "=" + edited, "--list"])
        assert r.returncode == 0 and "/ring_ao/" in r.stdout, r.stdout + r.stderr
        # A matrix value twice, or one no kernel of its group reads; quality
        # with a package's parameter for a kernel that does not declare it.
        # A value written twice in two forms ([0, false]) is twice too, and a
        # key of the group's own under params is sent to that key.
        for params, said, kernel in (('{"ring_px": [3, 3]}', "twice", "ring_ao"),
                                     ('{"ring_px": [3]}', "no kernel of the group reads it", "alchemy"),
                                     ('{"ring_pxx": [3]}', "has 'ring_pxx' (did you mean ring_px?)", "alchemy"),
                                     ('{"exact": [0, false]}', "params.exact has false twice", "alchemy_fast"),
                                     ('{"blur": [2]}', "in the group's own key 'blurs'", "alchemy")):
            bad = os.path.join(root, "bad_matrix")
            shutil.copytree(base, bad, dirs_exist_ok=True)
            json.dump({"mine": {"description": "d", "groups": [
                {"scenes": ["corner"], "kernels": [kernel], "samples": [8],
                 "blurs": [4], "params": json.loads(params), "resolutions": ["full"], "sizes": ["64x36"],
                 "apis": ["vk"], "stages": ["compute"]}]}}, open(os.path.join(bad, "matrices.json"), "w"))
            r = run([cavity, "gate", "--kernels", pkg, "--matrix", "mine", "--baselines", bad, "--list"])
            assert r.returncode == 2 and said in r.stderr, r.stderr
        r = run([cavity, "quality", "--kernels", pkg, "--kernel", "alchemy", "--ring_px", "3", "--list"])
        assert r.returncode == 2 and "--ring_px: no kernel measured declares it" in r.stderr, r.stderr

        # cavity ab passes the packages it loaded on to the builds it runs.
        r = run([cavity, "ab", "--kernels", pkg, "--a", bench, "--b", bench, "--filter", "/ring_ao/", "--bench-args",
                 "--sweep cpu", "--list"])
        assert r.returncode == 0 and "/ring_ao/" in r.stdout, r.stdout + r.stderr

        # The edit accepted as a user would: summary.md names the package's
        # file on disk and says how to accept images judged against approved
        # references. A baseline file would not replace those: update refuses
        # (it once wrote files named after the reference's digest) and
        # approve --with-kernel-source copies the edit into the package's
        # file (where the package lives, not into kernels/) with the digests.
        summary = open(os.path.join(root, "gate3", "summary.md")).read()
        assert "`" + os.path.join(pkg, "ring_ao.glsl") + "`" in summary, summary
        # ... by a command that runs as printed: this folder, the baselines
        # the gate was given, the package, and the edit (--with-kernel-source).
        assert ("`cavity baselines approve --from " + os.path.join(root, "gate3") + " --baselines " + base +
                " --kernels " + pkg +
                " --with-kernel-source --why ...`") in summary, summary
        listed = lambda d: sorted(os.listdir(d)) if os.path.isdir(d) else []
        before = listed(os.path.join(base, "images", "corner", "ring_ao", "n8", "b4", "full", "64x36"))
        r = run([cavity, "baselines", "update", "--kernels", pkg, "--from", os.path.join(root, "gate3"), "--baselines",
                 base, "--with-kernel-source"])
        assert r.returncode == 2 and "accept it with cavity baselines approve" in r.stderr, r.stdout + r.stderr
        assert listed(os.path.join(base, "images", "corner", "ring_ao", "n8", "b4", "full", "64x36")) == before
        assert open(os.path.join(pkg, "ring_ao.glsl")).read() != open(edited).read()
        r = run([cavity, "baselines", "approve", "--kernels", pkg, "--from", os.path.join(root, "gate3"), "--baselines",
                 base, "--why", "an edit", "--store", os.path.join(root, "store"), "--with-kernel-source"])
        assert r.returncode == 0 and "the packages now hold the edits" in r.stdout, r.stdout + r.stderr
        assert open(os.path.join(pkg, "ring_ao.glsl")).read() == open(edited).read()
        fourth = run(gate + ["--out", os.path.join(root, "gate4"), "--store", os.path.join(root, "store")])
        assert fourth.returncode == 0, fourth.stdout + fourth.stderr
        # A package edited after its gate: its images are not accepted (they
        # are not what its files render now).
        kept = open(os.path.join(pkg, "ring_ao.glsl")).read()
        with open(os.path.join(pkg, "ring_ao.glsl"), "a") as f:
            f.write("// edited after the gate\n")
        for accept in (["update"], ["approve", "--why", "x", "--store", os.path.join(root, "store")]):
            r = run([cavity, "baselines", *accept, "--kernels", pkg, "--from", os.path.join(root, "gate4"), "--baselines",
                     base, "--filter", "/ring_ao/"])
            assert r.returncode == 2 and "run the gate again" in r.stderr, accept + [r.stdout + r.stderr]
        with open(os.path.join(pkg, "ring_ao.glsl"), "w") as f:
            f.write(kept)

        # One package named through two paths loads once; a file is no folder.
        r = run([cavity, "kernels", "list", "--kernels", os.path.dirname(pkg), "--kernels", pkg])
        assert r.returncode == 0 and len(re.findall(r"^ring_ao ", r.stdout, re.M)) == 1, r.stdout + r.stderr
        r = run([cavity, "kernels", "list", "--kernels", os.path.join(pkg, "kernel.toml")])
        assert r.returncode == 2 and "is a file" in r.stderr, r.stderr

        # Two packages of one folder may declare the same new parameter alike.
        for name in ("ring_a", "ring_b"):
            make(os.path.join(root, "pair", name), toml=TOML.replace('"ring_ao"', f'"{name}"'))
        r = run([cavity, "kernels", "list", "--kernels", os.path.join(root, "pair")])
        assert r.returncode == 0 and "ring_a" in r.stdout and "ring_b" in r.stdout, r.stdout + r.stderr

        # Shards rendered from two versions of a package are not judged as one.
        render = os.path.join(build, "render", "cavity_render")
        for shard in (0, 1):
            r = run([render, "--kernels", pkg, "--matrix", "mine", "--baselines", base, "--shard", f"{shard}/2",
                     "--out", os.path.join(root, f"shard{shard}")])
            assert r.returncode == 0, r.stderr
            with open(os.path.join(pkg, "ring_ao.glsl"), "a") as f:
                f.write("// edited between the shards\n")
        r = run([cavity, "gate", "judge", "--kernels", pkg, "--baselines", base, "--out", os.path.join(root, "judged"),
                 os.path.join(root, "shard0"), os.path.join(root, "shard1")])
        assert r.returncode == 2 and "(render every shard with the same --kernels)" in r.stderr, r.stderr
        # ... while shards of one version are, though one holds only a
        # built-in kernel; and each manifest's command loads the package.
        mixed = json.load(open(os.path.join(base, "matrices.json")))
        mixed["mixed"] = {"description": "a built-in and the package", "groups": [
            {"scenes": ["corner"], "kernels": ["alchemy", "ring_ao"], "samples": [8], "blurs": [4],
             "resolutions": ["full"], "sizes": ["64x36"], "apis": ["vk"], "stages": ["compute"]}]}
        json.dump(mixed, open(os.path.join(base, "matrices.json"), "w"))
        for shard in (0, 1):
            r = run([render, "--kernels", pkg, "--matrix", "mixed", "--baselines", base, "--shard", f"{shard}/2",
                     "--out", os.path.join(root, f"mixed{shard}")])
            assert r.returncode == 0, r.stderr
            manifest = json.load(open(os.path.join(root, f"mixed{shard}", "manifest.json")))
            assert shlex.split(manifest["command"])[1:3] == ["--kernels", pkg], manifest["command"]
        r = run([cavity, "gate", "judge", "--kernels", pkg, "--baselines", base, "--out", os.path.join(root, "judged_mixed"),
                 os.path.join(root, "mixed0"), os.path.join(root, "mixed1")])
        assert "render every shard" not in r.stderr and os.path.exists(os.path.join(root, "judged_mixed", "gate.json")), \
            r.stdout + r.stderr

        failures += check_flag_names(cavity, bench, render, root)
        failures += check_disagreement(cavity, root)
        failures += check_builtins_and_outputs(cavity, root, source)
        failures += check_unknown_reference(cavity, root)
        failures += check_bad(cavity, root)
    print(f"packages: {'passed' if not failures else str(failures) + ' failed'}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
