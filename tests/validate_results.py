#!/usr/bin/env python3
"""A real consumer of results.json: python3-jsonschema validates what `cavity
run` wrote against harness/measure/results.schema.json, and the timing record is
checked against the samples it describes. On a software renderer every floor
is null with its reason; a pass with no declared cost (the rasterised
G-buffer) says so; and a copy of a run given an H200's figures and floors
validates, while one with a floor field wrong does not, so the schema's
floor branch is checked as well as its null one.

    validate_results.py CAVITY_EXE SOURCE_DIR
"""
import copy
import json
import os
import subprocess
import sys
import tempfile

import jsonschema


def main():
    cavity, source = sys.argv[1], sys.argv[2]
    schema = json.load(open(os.path.join(source, "harness", "measure", "results.schema.json")))
    jsonschema.Draft202012Validator.check_schema(schema)
    with tempfile.TemporaryDirectory() as out:
        for timing in ("batch", "drained"):
            r = subprocess.run([cavity, "run", "--backend", "all", "--res", "64x36", "--frames", "4", "--warmup", "1",
                                "--timing", timing, "--max-noise", "0", "--resolution", "full,half", "--out", out],
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.exit(f"cavity run --timing {timing} exited {r.returncode}: {r.stderr}")
            doc = json.load(open(os.path.join(out, "results.json")))
            jsonschema.Draft202012Validator(schema).validate(doc)
            if not doc["runs"]:
                sys.exit("results.json has no runs")
            for run in doc["runs"]:
                t = run["timing"]
                measured = run["frames"]["measured"]
                if measured != 4 or any(len(p["samples_ms"]) != measured for p in run["passes"]):
                    sys.exit(f"{run['id']}: {measured} frames measured, passes hold "
                             f"{[len(p['samples_ms']) for p in run['passes']]} samples; asked for 4")
                expected = timing if run["clock"] == "gpu-timestamp" else "drained"
                if t["mode"] != expected or t["mode_requested"] != timing:
                    sys.exit(f"{run['id']}: timing mode {t['mode']} (asked {t['mode_requested']}), expected {expected}")
                if t["stop"] != "frames" or t["rejected_frames"] < 0:
                    sys.exit(f"{run['id']}: stop {t['stop']}, rejected {t['rejected_frames']}")
                check_floors(run)
                check_shader_stats(run)
            print(f"--timing {timing}: {len(doc['runs'])} runs valid")
        r = subprocess.run([cavity, "run", "--backend", "vk", "--gbuffer", "raster", "--res", "64x36", "--frames", "2",
                            "--warmup", "0", "--max-noise", "0", "--out", out], capture_output=True, text=True)
        if r.returncode != 0:
            sys.exit(f"cavity run --gbuffer raster exited {r.returncode}: {r.stderr}")
        doc = json.load(open(os.path.join(out, "results.json")))
        jsonschema.Draft202012Validator(schema).validate(doc)
        gbuffer = [p for run in doc["runs"] for p in run["passes"] if p["name"] == "gbuffer"]
        if not gbuffer or any(p["floor"] is not None or p["floor_reason"] != "no cost declared" for p in gbuffer):
            sys.exit(f"raster G-buffer: expected floor null, 'no cost declared'; got {[(p['floor'], p['floor_reason']) for p in gbuffer]}")
        print("--gbuffer raster: the G-buffer pass has no cost declared")
        check_floor_branch(schema, doc["runs"][0])
        check_shader_stats_branch(schema, doc["runs"][0])


def check_floors(run):
    """Every floor is null and says why on a software renderer; a GPU in
    the floor table has figures, and each pass a floor or a reason."""
    software = run["device"]["software_renderer"]
    if software:
        if run["floor_device"] is not None or "software renderer" not in run["floor_device_reason"]:
            sys.exit(f"{run['id']}: software renderer, but floor_device {run['floor_device']!r}, "
                     f"reason {run['floor_device_reason']!r}")
    for p in run["passes"]:
        if (p["floor"] is None) == (p["floor_reason"] == ""):
            sys.exit(f"{run['id']} {p['name']}: floor {p['floor']!r} with reason {p['floor_reason']!r}")
        if software and p["floor_reason"] != run["floor_device_reason"]:
            sys.exit(f"{run['id']} {p['name']}: reason {p['floor_reason']!r}, expected the device's")


def check_shader_stats(run):
    """Each pass has the driver's statistics or says why not: GL never has
    them, and neither do the CPU renderers CI runs (lavapipe in Debian 12
    lacks VK_KHR_pipeline_executable_properties)."""
    for p in run["passes"]:
        if (not p["shader_stats"]) == (p["shader_stats_reason"] == ""):
            sys.exit(f"{run['id']} {p['name']}: shader_stats {p['shader_stats']!r} with reason {p['shader_stats_reason']!r}")
        if run["backend"] == "gl" and "OpenGL" not in p["shader_stats_reason"]:
            sys.exit(f"{run['id']} {p['name']}: GL pass with reason {p['shader_stats_reason']!r}")


def check_shader_stats_branch(schema, run):
    """The statistics NVIDIA's driver reported on the H200
    (in the shader-statistics study of 2026-12-03) validate; spoiled copies do not."""
    run = copy.deepcopy(run)
    for p in run["passes"]:
        p["shader_stats"] = [{"executable": "CS", "name": "Register Count", "value": 31},
                             {"executable": "CS", "name": "Binary Size", "value": 6528}]
        p["shader_stats_reason"] = ""
    check_spoiled(schema, run, "shader statistics: valid with an H200's", {
        "a statistic whose value is text": lambda d: d["runs"][0]["passes"][0]["shader_stats"][0].update(value="31"),
        "a statistic without its executable": lambda d: d["runs"][0]["passes"][0]["shader_stats"][0].pop("executable"),
        "a pass without shader_stats_reason": lambda d: d["runs"][0]["passes"][0].pop("shader_stats_reason"),
    })


def check_spoiled(schema, run, what_valid, wrong):
    """`run` as a results.json of one run validates; each spoiled copy
    (wrong: what it is -> the spoiling) does not."""
    doc = {"schema": "cavity.results/1", "git_commit": "x", "created_utc": "2026-12-01T00:00:00Z", "command": "",
           "errors": [], "runs": [run]}
    validator = jsonschema.Draft202012Validator(schema)
    validator.validate(doc)
    for what, spoil in wrong.items():
        bad = copy.deepcopy(doc)
        spoil(bad)
        if validator.is_valid(bad):
            sys.exit(f"the schema accepts {what}")
    print(f"{what_valid}, {len(wrong)} spoiled copies rejected")


def check_floor_branch(schema, run):
    """The H200's figures and the alchemy n16 floor at 1920x1080 (tests/test_roofline.cpp) as
    `cavity run` writes them validate; each of a few wrong ones does not."""
    table = {"value": 0, "source": "table:NVIDIA H200"}
    run = copy.deepcopy(run)
    run["floor_device"] = {"name": "NVIDIA H200", "sm_count": dict(table, value=132, source="driver"),
                           "texture_units_per_sm": dict(table, value=4), "sm_clock_mhz": dict(table, value=1980, source="nvml"),
                           "dram_gb_per_s": dict(table, value=4800), "fetch_slots_per_s": 1.04544e12,
                           "table_source": "NVIDIA H200 data sheet"}
    run["floor_device_reason"] = ""
    for p in run["passes"]:
        p["floor"] = {"floor_ms": 0.138843, "fetch_floor_ms": 0.138843, "dram_floor_ms": 0.011232, "bound": "fetch",
                      "measured_over_floor": 1.43, "pixels": 2073600, "fetches_per_pixel": 18,
                      "fetch_slots_per_pixel": 70, "bytes_per_pixel": 282, "dram_bytes_per_pixel": 26}
        p["floor_reason"] = ""
    check_spoiled(schema, run, "floor branch: valid with an H200's figures", {
        "a bound that is neither fetch nor dram": lambda d: d["runs"][0]["passes"][0]["floor"].update(bound="alu"),
        "a floor without floor_ms": lambda d: d["runs"][0]["passes"][0]["floor"].pop("floor_ms"),
        "a zero DRAM floor": lambda d: d["runs"][0]["passes"][0]["floor"].update(dram_floor_ms=0),
        "a figure of unknown source": lambda d: d["runs"][0]["floor_device"]["sm_count"].update(source="guess"),
        "a figure without its source": lambda d: d["runs"][0]["floor_device"]["dram_gb_per_s"].pop("source"),
        "a pass without floor_reason": lambda d: d["runs"][0]["passes"][0].pop("floor_reason"),
    })


if __name__ == "__main__":
    main()
