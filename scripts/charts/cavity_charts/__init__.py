"""Charts from Cavity's benchmark results, drawn with matplotlib; the command
line is scripts/charts/charts.py (cli.py here).

    inputs.py        reading cavity_bench (Google Benchmark) JSON, quality.json and
                     results.json, plain or gzip (scripts/charts/cavity_json.py)
    labels.py        how devices, slices, series and files are written on a chart
    plotting.py      pick_slice (the slice a chart draws) and Canvas (matplotlib set
                     up, title block, legend, log axes, PNG + SVG written and listed)
    time_vs_samples.py, time_vs_blur.py, full_vs_half.py, time_vs_megapixels.py,
    gl_vs_vk.py, compute_vs_fragment.py, history.py
                     one chart each of the main command: draw(canvas)
    quality_cost.py  the quality-cost subcommand
    floor.py         the floor subcommand
    cli.py           the command line: main(argv)

Nothing here imports matplotlib until a chart is drawn, so the loaders and the
computations can be imported (and tested) without it.
"""
