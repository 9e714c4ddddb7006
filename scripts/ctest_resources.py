#!/usr/bin/env python3
"""Writes CTest's resource specification (a JSON file for
`ctest --resource-spec-file`) listing this machine's GPUs, so that
`ctest -L gate -j N --resource-spec-file F` runs the gate's shards one per GPU
(tests/CMakeLists.txt: each shard asks for `gpus:1`).

    scripts/ctest_resources.py --out build/resources.json            # the devices found
    scripts/ctest_resources.py --devices 0 --per-device 2 --out F    # device 0 twice

Devices, first that answers: `vulkaninfo --summary` (its GPU0, GPU1, ...
blocks; CPU devices such as lavapipe only when nothing else is there),
`nvidia-smi -L`, /dev/dri/renderD* (EGL devices), and otherwise one device,
index 0 (a software renderer). An index is what `cavity gate --device K`
takes. Resource ids are `K`, or `K_J` with --per-device above 1 (J-th share
of device K: several shards on one large GPU, or two "GPUs" on one software
renderer in the CI test); tests/ctest_gate_shard.sh reads the device index
back from the id CTest hands it. Bad arguments: one line, exit 2.
"""
import argparse
import glob
import json
import os
import re
import shutil
import subprocess
import sys


def vulkan_devices():
    if not shutil.which("vulkaninfo"):
        return None
    try:
        out = subprocess.run(["vulkaninfo", "--summary"], capture_output=True, text=True, timeout=60).stdout
    except (OSError, subprocess.TimeoutExpired):
        return None
    devices, current = [], None
    for line in out.splitlines():
        m = re.match(r"\s*GPU(\d+):", line)
        if m:
            current = {"index": int(m.group(1)), "type": ""}
            devices.append(current)
        elif current is not None and "deviceType" in line:
            current["type"] = line.split("=", 1)[-1].strip()
    if not devices:
        return None
    real = [d["index"] for d in devices if "CPU" not in d["type"]]
    return real or [d["index"] for d in devices]


def nvidia_devices():
    if not shutil.which("nvidia-smi"):
        return None
    try:
        out = subprocess.run(["nvidia-smi", "-L"], capture_output=True, text=True, timeout=60).stdout
    except (OSError, subprocess.TimeoutExpired):
        return None
    n = len([l for l in out.splitlines() if l.startswith("GPU ")])
    return list(range(n)) or None


def dri_devices():
    n = len(glob.glob("/dev/dri/renderD*"))
    return list(range(n)) or None


def parse_devices(text):
    try:
        devices = [int(x) for x in text.split(",")]
    except ValueError:
        devices = []
    if not devices or any(d < 0 or d > 64 for d in devices):
        raise ValueError(f"--devices {text}: must be a comma-separated list of device indices 0..64")
    return devices


def spec(devices, per_device):
    gpus = []
    for d in devices:
        for j in range(per_device):
            gpus.append({"id": str(d) if per_device == 1 else f"{d}_{j}", "slots": 1})
    return {"version": {"major": 1, "minor": 0}, "local": [{"gpus": gpus}]}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--out", required=True, help="resource spec file to write")
    p.add_argument("--devices", help="comma-separated device indices instead of detecting them")
    p.add_argument("--per-device", default="1", help="resource ids per device (default 1)")
    a = p.parse_args()
    try:
        per = int(a.per_device)
        if not 1 <= per <= 64:
            raise ValueError
    except ValueError:
        print(f"ctest_resources.py: --per-device {a.per_device}: must be an integer in 1..64", file=sys.stderr)
        return 2
    if a.devices is not None:
        try:
            devices = parse_devices(a.devices)
        except ValueError as e:
            print(f"ctest_resources.py: {e}", file=sys.stderr)
            return 2
    else:
        devices = vulkan_devices() or nvidia_devices() or dri_devices() or [0]
    out_dir = os.path.dirname(os.path.abspath(a.out))
    if not os.path.isdir(out_dir):
        print(f"ctest_resources.py: --out {a.out}: folder {out_dir} does not exist", file=sys.stderr)
        return 2
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(spec(devices, per), f, indent=2)
        f.write("\n")
    os.replace(tmp, a.out)
    print(f"{a.out}: {len(devices) * per} gpus on devices {','.join(map(str, devices))}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
