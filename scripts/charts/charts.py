#!/usr/bin/env python3
"""Charts from cavity_bench results (Google Benchmark JSON).

    python3 scripts/charts/charts.py RESULT.json [MORE.json ...] --out DIR [--title TEXT]

Writes DIR/<chart>.png (150 dpi) and DIR/<chart>.svg for every chart the data
has an axis for, DIR/index.json listing them (name, title, png, svg), and
prints the path of each file written. Charts 1-6 use the LAST file given; with
two or more files, the history chart follows each configuration across all of
them in the order given.

  time_vs_samples      GPU time against AO samples per pixel, a line per (kernel, API)
  time_vs_blur         GPU time against bilateral blur radius
  full_vs_half         full vs half resolution bars, speed-up (full/half) above each pair
  time_vs_megapixels   GPU time against image size, with a linear fit through the origin
  gl_vs_vk             OpenGL time against Vulkan time for the same configuration
  compute_vs_fragment  compute vs fragment stage bars, ratio above each pair
  history              time of each configuration across the files given

Each chart fixes every other configuration axis at one value (preferring
1920x1080 and the compute stage, then the slice with the most points) and says
which in its subtitle. A chart whose axis the data lacks is skipped with a note
on stderr.

Input: the JSON cavity_bench writes with --benchmark_format=json or
--benchmark_out. Benchmark names are configuration ids,
    <scene>/<kernel>/n<samples>/b<blur>/<full|half>/<W>x<H>/<gl|vk>/<compute|fragment>
to which Google Benchmark appends "/iterations:N", "/manual_time" and, for
aggregates, "_median" etc. The time charted is real_time (the manual GPU time
of the AO part of the pipeline), in ms; the "median" aggregate is used where
repetitions were run, else the mean of the iteration entries.

Exit codes: 0 written; 2 bad usage or input (one line on stderr names the file
and what is wrong; nothing is written); 3 matplotlib is missing.

Subcommand: quality against cost

    python3 scripts/charts/charts.py quality-cost --quality Q.json [Q.json ...] --bench BENCH.json [...] --out DIR
                              [--api vk|gl] [--size WxH] [--note TEXT]

plots each AO kernel x sample count x full/half as one point: the error
against the ground truth (mean over the scenes of each `cavity quality`
row's MAE; quality.json, schema cavity.quality/1, one file per resolution)
against the AO passes' GPU time from cavity_bench JSON (the median over
repetitions of pass_ao_ms plus the passes that belong to the AO estimate:
depth, pyramid, box, downsample, upsample; the bilateral blur and composite are the
same for every kernel and left out) of corner/<kernel>/n<N>/b4/<res>/<size>/
<api>/compute. The Pareto front (no other point both faster and closer to
the truth) is drawn and its points ringed. Writes DIR/quality_cost.png,
.svg and quality_cost.json (the joined points, front marked). A quality row
with no benchmark (or the reverse) is listed on stderr and left out.

Subcommand: measured against floor

    python3 scripts/charts/charts.py floor RESULTS.json [MORE.json ...] --out DIR [--filter REGEX]

reads `cavity run`'s results.json (schema cavity.results/1), or cavity_bench's
JSON (each `<id>@<pass>` entry's median over the repetitions), and draws, one row
per pass of every configuration, the measured median (a bar, log scale) and
the pass's floor (a black tick; bench/ROOFLINE.md), with measured/floor at the
end of the row. A pass with no floor (a software renderer, a device not in
the floor table, no cost declared) has its bar in grey and its reason at the
end of the row; a file with no floor at all says so on stderr and in the
title, and draws the measured times. Writes DIR/floor.png, DIR/floor.svg.

Uses only the Python standard library and matplotlib (Debian's python3-matplotlib).
"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))   # cavity_charts/ and cavity_json.py beside this file

# The package's names, for `import charts` (scripts/charts/test_charts.py and anyone else who did).
from cavity_charts.cli import CHART_NAMES, CHARTS, SUBCOMMANDS, main, parse_args  # noqa: E402,F401
from cavity_charts.compute_vs_fragment import fragment_ratios  # noqa: E402,F401
from cavity_charts.floor import main as floor_main  # noqa: E402,F401
from cavity_charts.full_vs_half import speedups  # noqa: E402,F401
from cavity_charts.gl_vs_vk import api_pairs  # noqa: E402,F401
from cavity_charts.history import HISTORY_MAX_LINES, history_series  # noqa: E402,F401
from cavity_charts.inputs import (DIMS, BadInput, bench_floor_rows, config_id, load_floor_rows,  # noqa: E402,F401
                                  load_quality, load_results, parse_id, strip_name)
from cavity_charts.labels import (API_NAMES, device_line, device_name, driver_name, file_label,  # noqa: E402,F401
                                  fixed_line, format_ratio, is_compute_card, series_label, short_ids, shorten)
from cavity_charts.plotting import DPI, Canvas, kernel_colours, pick_slice  # noqa: E402,F401
from cavity_charts.quality_cost import AO_COST_PASSES, is_screen_space, join_quality_cost, pareto_front  # noqa: E402,F401
from cavity_charts.quality_cost import main as quality_cost_main  # noqa: E402,F401
from cavity_charts.time_vs_megapixels import fit_through_origin  # noqa: E402,F401

if __name__ == "__main__":
    sys.exit(main())
