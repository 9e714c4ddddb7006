"""The command line of scripts/charts/charts.py: the main command (every time chart
from cavity_bench JSON or results.json) and the subcommands quality-cost and floor."""

import argparse
import importlib.util
import json
import os
import sys
import textwrap

from . import (compute_vs_fragment, floor, full_vs_half, gl_vs_vk, history, passes, quality_cost, time_vs_blur,
               time_vs_megapixels, time_vs_samples)
from .inputs import BadInput, load_results
from .labels import device_line
from .plotting import Canvas

# The main command's charts, in the order drawn and listed in index.json.
CHARTS = (time_vs_samples, time_vs_blur, full_vs_half, time_vs_megapixels, gl_vs_vk, compute_vs_fragment, passes,
          history)
CHART_NAMES = tuple(m.NAME for m in CHARTS)
# Subcommands: the first argument picks one; anything else is the main command.
SUBCOMMANDS = {"quality-cost": quality_cost, "floor": floor}
SCRIPT = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "charts.py")
USAGE = "charts.py RESULT.json [MORE.json ...] --out DIR [--title TEXT] [--filter REGEX]"


def summary(module):
    """The first paragraph of a module's docstring, without its "name: "."""
    first = module.__doc__.strip().split("\n\n")[0]
    return " ".join(first.split(": ", 1)[1].split())


def epilog():
    width = max(len(n) for n in CHART_NAMES) + 2

    def item(name, text):
        return textwrap.fill(text, 100, initial_indent=f"  {name:<{width}}", subsequent_indent=" " * (width + 2))

    lines = ["charts of the main command (each one the data has an axis for: NAME.png and NAME.svg, and",
             "index.json listing them; the last RESULT.json is charted, history follows all of them):"]
    lines += [item(m.NAME, summary(m)) for m in CHARTS]
    lines += ["", "subcommands (charts.py SUBCOMMAND --help for the options of each):"]
    for name, module in SUBCOMMANDS.items():
        lines += [item(name, summary(module)),
                  item("", " ".join(module.__doc__.strip().split("\n\n")[1].split()))]
    lines += ["", "A RESULT.json may be gzip (X.json.gz). Exit codes: 0 written; 2 bad usage or input; "
              "3 matplotlib is missing."]
    return "\n".join(lines)


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        # one line, like every other bad-usage error of the project
        print(f"charts: {message} (usage: {USAGE})", file=sys.stderr)
        sys.exit(2)


def parse_args(argv):
    p = _Parser(prog="charts", description="Charts from cavity_bench's Google Benchmark JSON or cavity run's "
                "results.json: the median of each configuration's repetitions (or frames) with their "
                "interquartile range as whiskers, on the clock they were timed on.",
                usage="\n  ".join(["", USAGE] + [f"charts.py {n} ... (charts.py {n} --help)" for n in SUBCOMMANDS]),
                epilog=epilog(), formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results", nargs="+", metavar="RESULT.json")
    p.add_argument("--out", required=True, metavar="DIR")
    p.add_argument("--title", default="", metavar="TEXT", help="prefix for every chart title")
    p.add_argument("--filter", default="", metavar="REGEX",
                   help="only the configurations whose id this regex finds (a chart shows at most 8 series)")
    return p.parse_args(argv)


def keep_only(files, pattern):
    """Every file's records narrowed to the ids `pattern` finds; BadInput when
    it is no regular expression or the last file (the one charted) keeps none."""
    import re
    try:
        keep = re.compile(pattern)
    except (re.error, RecursionError, OverflowError) as e:   # nested past what re compiles
        shown = pattern if len(pattern) <= 60 else pattern[:57] + "..."
        raise BadInput(f"charts: --filter {shown!r}: not a regular expression ({str(e) or type(e).__name__})")
    for f in files:
        f["records"] = {k: r for k, r in f["records"].items() if keep.search(r["id"])}
    if not files[-1]["records"]:
        raise BadInput(f"charts: --filter {pattern!r} matches no configuration of {files[-1]['path']}")


def run_with_system_python(argv):
    """pyenv or a venv without matplotlib: Debian's python3-matplotlib lives with /usr/bin/python3,
    so every subcommand runs again there (once)."""
    if importlib.util.find_spec("matplotlib") is not None:
        return
    system = "/usr/bin/python3"
    if os.path.exists(system) and os.path.realpath(sys.executable) != os.path.realpath(system) \
            and not os.environ.get("CAVITY_CHARTS_REEXEC"):
        os.environ["CAVITY_CHARTS_REEXEC"] = "1"
        sys.stdout.flush()
        os.execv(system, [system, SCRIPT] + argv)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    run_with_system_python(argv)
    if argv and argv[0] in SUBCOMMANDS:
        return SUBCOMMANDS[argv[0]].main(argv[1:])
    args = parse_args(argv)
    # Validate every input before writing anything.
    try:
        files = [load_results(p) for p in args.results]
        if args.filter:
            keep_only(files, args.filter)
        # A title is one line above each chart: a longer one cannot be
        # drawn (matplotlib overflows its glyph raster) and would hide the chart.
        if len(args.title) > 200 or "\n" in args.title:
            raise BadInput(f"charts: --title: {len(args.title)} characters{' with a line break' if chr(10) in args.title else ''}"
                           f" (at most 200, on one line)")
        if os.path.exists(args.out) and not os.path.isdir(args.out):
            raise BadInput(f"charts: {args.out}: --out exists and is not a folder")
    except BadInput as e:
        print(str(e), file=sys.stderr)
        return 2
    if importlib.util.find_spec("matplotlib") is None:
        print("charts: matplotlib is not installed (apt-get install python3-matplotlib)", file=sys.stderr)
        return 3
    for f in files:
        if f["dropped"]:
            print(f"charts: note: {f['path']}: left out {len(f['dropped'])} configuration(s) timed at 0 ms, "
                  f"e.g. {f['dropped'][0]}", file=sys.stderr)
    created = not os.path.isdir(args.out)
    try:
        os.makedirs(args.out, exist_ok=True)
    except OSError as e:
        print(f"charts: --out {args.out!r}: cannot create the output folder ({e.strerror})", file=sys.stderr)
        return 2
    # charts a previous run wrote that this run may not: index.json must not disagree with the folder
    for name in CHART_NAMES:
        for ext in (".png", ".svg"):
            stale = os.path.join(args.out, name + ext)
            if os.path.isfile(stale):
                os.remove(stale)
    canvas = Canvas(files, args.out, args.title)
    try:
        for chart in CHARTS:
            chart.draw(canvas)
    except BaseException:
        if created:
            import shutil
            shutil.rmtree(args.out, ignore_errors=True)
        raise
    index = {
        "charts": canvas.written,
        "skipped": canvas.skipped,
        "sources": [{"file": f["path"], "date": f["date"], "device": device_line(f["context"])} for f in files],
    }
    path = os.path.join(args.out, "index.json")
    with open(path, "w") as f:
        json.dump(index, f, indent=2)
        f.write("\n")
    print(path)
    return 0
