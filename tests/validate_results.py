#!/usr/bin/env python3
"""A real consumer of results.json: python3-jsonschema validates what `cavity
run` wrote against harness/results.schema.json, and the timing record is
checked against the samples it describes.

    validate_results.py CAVITY_EXE SOURCE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

import jsonschema


def main():
    cavity, source = sys.argv[1], sys.argv[2]
    schema = json.load(open(os.path.join(source, "harness", "results.schema.json")))
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
            print(f"--timing {timing}: {len(doc['runs'])} runs valid")


if __name__ == "__main__":
    main()
