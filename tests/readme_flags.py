#!/usr/bin/env python3
"""The documentation's commands against the binaries' --help.

    readme_flags.py CAVITY SOURCE_DIR [CAVITY_RENDER CAVITY_BENCH]

1. README.md's `cavity run` flag table (between the markers
   `<!-- cavity-run-flags: begin -->` and `<!-- cavity-run-flags: end -->`)
   lists exactly the flags `cavity run --help` prints, which are generated
   from the declarations.
2. Every command in README.md and docs/*.md that invokes cavity,
   cavity_render or cavity_bench (in a code block, or an inline code span
   that starts with the program) names a subcommand that exists (its
   `--help` exits 0) and uses only flags that appear in that subcommand's
   `--help`. `.bundle/run.sh` and `.bundle/render.sh` (scripts/bundle.sh)
   stand for cavity_bench and cavity_render. cavity_bench passes
   `--benchmark_*` flags to Google Benchmark, whose flags its `--help` does
   not list: those are checked against Google Benchmark's own list below.

Without CAVITY_RENDER and CAVITY_BENCH they are looked for beside CAVITY's
build folder (build/harness/cavity -> build/render/cavity_render,
build/bench/cavity_bench). Exit 0 when everything holds, 1 otherwise.
"""
import glob
import os
import re
import subprocess
import sys

BEGIN, END = "<!-- cavity-run-flags: begin -->", "<!-- cavity-run-flags: end -->"
FLAG = re.compile(r"--[A-Za-z0-9][A-Za-z0-9_-]*")
# Google Benchmark 1.7's command-line flags (benchmark.cc), which
# cavity_bench hands on untouched.
GOOGLE_BENCHMARK_FLAGS = {
    "--benchmark_list_tests", "--benchmark_filter", "--benchmark_min_time", "--benchmark_min_warmup_time",
    "--benchmark_repetitions", "--benchmark_enable_random_interleaving", "--benchmark_report_aggregates_only",
    "--benchmark_display_aggregates_only", "--benchmark_format", "--benchmark_out", "--benchmark_out_format",
    "--benchmark_color", "--benchmark_counters_tabular", "--benchmark_perf_counters", "--benchmark_context",
    "--benchmark_time_unit", "--v",
}
# Subcommands: program -> {subcommand words: ()}; () is the program itself.
SUBCOMMANDS = {
    "cavity": [("run",), ("quality",), ("compare",), ("gate", "judge"), ("gate", "merge"), ("gate",),
               ("baselines", "update"), ("baselines", "approve"), ("baselines", "migrate-digests"), ("store", "check"), ("ab",),
               ("history", "ingest"), ("history", "show"), ("history", "chart"), ("history", "alerts"),
               ("history",), ("kernels", "list"), ("kernels", "show"), ("kernels", "check"), ("kernels", "coverage")],
    "cavity_render": [("quality",)],
    "cavity_bench": [],
}
SEPARATORS = {"&&", "||", ";", "|", "&", ">", ">>", "2>", "<"}

failures = []


def fail(msg):
    failures.append(msg)
    print(f"FAIL {msg}")


def program_of(word):
    """The program a command word names, or None."""
    word = word.strip("`")
    base = word.rsplit("/", 1)[-1]
    if base in SUBCOMMANDS and (word == base or word.endswith("/" + base)):
        return base
    if word.endswith(".bundle/run.sh"):
        return "cavity_bench"
    if word.endswith(".bundle/render.sh"):
        return "cavity_render"
    return None


class Helps:
    def __init__(self, paths):
        self.paths, self.cache = paths, {}

    def flags(self, program, sub):
        """Flags of `program sub --help`, or None when it does not exit 0."""
        key = (program, sub)
        if key not in self.cache:
            exe = self.paths[program]
            r = subprocess.run([exe, *sub, "--help"], capture_output=True, text=True, timeout=60)
            self.cache[key] = set(FLAG.findall(r.stdout)) if r.returncode == 0 and r.stdout else None
            if self.cache[key] is None:
                fail(f"{program} {' '.join(sub)} --help: exit {r.returncode}, stdout {len(r.stdout)} chars")
        return self.cache[key]


def check_table(helps, readme):
    helped = helps.flags("cavity", ("run",))
    if helped is None:
        return
    # the option lines only ("  --flag ..." at the start of a line), not
    # flags the help text mentions
    r = subprocess.run([helps.paths["cavity"], "run", "--help"], capture_output=True, text=True)
    helped = set(re.findall(r"^\s+(--[a-z_-]+)", r.stdout, re.M)) - {"--help"}
    if BEGIN not in readme or END not in readme:
        fail(f"README.md: the markers {BEGIN} and {END} around the cavity run flag table are missing")
        return
    section = readme[readme.index(BEGIN):readme.index(END)]
    tabled = set()
    for row in section.splitlines():
        if row.startswith("| `--"):
            tabled.update(re.findall(r"`(--[a-z_-]+)`", row.split("|")[1]))
    for f in sorted(helped - tabled):
        fail(f"{f}: printed by cavity run --help, not in README's flag table")
    for f in sorted(tabled - helped):
        fail(f"{f}: in README's flag table, not a flag of cavity run --help")
    print(f"flag table: {len(helped)} flags of cavity run --help")


def code_commands(text):
    """(line number, command text) of every line of a code block, with
    backslash continuations and synopsis continuations ("   [--flag ...")
    joined, and of every inline code span."""
    out = []
    lines = text.split("\n")
    in_fence, prev_blank, in_indented = False, True, False
    block = []  # (lineno, text) of the current block
    blocks = []
    for i, line in enumerate(lines, 1):
        if line.lstrip().startswith("```"):
            if in_fence:
                blocks.append(block)
                block = []
            in_fence = not in_fence
            prev_blank = False
            continue
        if in_fence:
            block.append((i, line))
            continue
        indented = line.startswith("    ") and line.strip() != ""
        starts_list = line.lstrip().startswith(("- ", "* ", "|"))
        if indented and (in_indented or (prev_blank and not starts_list)):
            in_indented = True
            block.append((i, line))
        elif line.strip() == "" and in_indented:
            block.append((i, line))
        else:
            if in_indented:
                blocks.append(block)
                block = []
            in_indented = False
        prev_blank = line.strip() == ""
    if block:
        blocks.append(block)
    for block in blocks:
        current = None
        for n, line in block:
            s = line.strip()
            if current and (current[1].endswith("\\") or s.startswith("[--")):
                current = (current[0], current[1].rstrip("\\") + " " + s)
                continue
            if current:
                out.append(current)
            current = (n, s) if s else None
        if current:
            out.append(current)
    # inline code spans (outside code blocks: strip the blocks first)
    stripped = list(lines)
    for block in blocks:
        for n, _ in block:
            stripped[n - 1] = ""
    flat = "\n".join(stripped)
    for m in re.finditer(r"(?<!`)`([^`\n]+(?:\n[^`\n]+)?)`(?!`)", flat):
        words = m.group(1).split()
        if words and program_of(words[0]):
            out.append((flat.count("\n", 0, m.start()) + 1, " ".join(words)))
    return out


def invocations(command):
    """(program, args) of every invocation in a shell command line."""
    command = re.sub(r"(^|\s)#.*$", "", command)  # a comment
    words = command.replace("`", " ").split()
    found = []
    for i, w in enumerate(words):
        p = program_of(w)
        if not p:
            continue
        args = []
        for a in words[i + 1:]:
            if a in SEPARATORS or program_of(a):
                break
            args.append(a)
        found.append((p, args))
    return found


def check_command(helps, where, program, args):
    positional = [a for a in args if not a.lstrip("[").startswith("-")]
    sub = ()
    for candidate in SUBCOMMANDS[program]:
        if tuple(positional[:len(candidate)]) == candidate and args[:len(candidate)] == list(candidate):
            sub = candidate
            break
    if program == "cavity" and not sub and args and not args[0].startswith("-"):
        fail(f"{where}: cavity {args[0]}: not a command of cavity")
        return
    flags = helps.flags(program, sub)
    if flags is None:
        return
    name = " ".join((program,) + sub)
    for a in args[len(sub):]:
        for f in FLAG.findall(a.lstrip("[")):
            if not a.lstrip("[(").startswith(f):
                continue  # a flag inside a value, e.g. a quoted filter
            if f in flags or f in ("--help", "-h"):
                continue
            if program == "cavity_bench" and f in GOOGLE_BENCHMARK_FLAGS:
                continue
            fail(f"{where}: {name}: {f} is not in `{name} --help`")
            break


def main():
    if len(sys.argv) not in (3, 5):
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    cavity, source = sys.argv[1], sys.argv[2]
    build = os.path.dirname(os.path.dirname(os.path.abspath(cavity)))
    render = sys.argv[3] if len(sys.argv) == 5 else os.path.join(build, "render", "cavity_render")
    bench = sys.argv[4] if len(sys.argv) == 5 else os.path.join(build, "bench", "cavity_bench")
    paths = {"cavity": cavity, "cavity_render": render, "cavity_bench": bench}
    for p, exe in paths.items():
        if not os.access(exe, os.X_OK):
            print(f"FAIL {p}: {exe} is not an executable (give CAVITY_RENDER and CAVITY_BENCH)")
            sys.exit(1)
    helps = Helps(paths)
    readme = open(os.path.join(source, "README.md"), encoding="utf-8").read()
    check_table(helps, readme)

    docs = [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md")))
    checked = 0
    for path in docs:
        rel = os.path.relpath(path, source)
        for line, command in code_commands(open(path, encoding="utf-8").read()):
            for program, args in invocations(command):
                check_command(helps, f"{rel}:{line}", program, args)
                checked += 1
    print(f"{checked} documented commands in {len(docs)} files; {len(failures)} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
