#!/usr/bin/env python3
"""Writes the three planted variants of kernels/ssao_alchemy_fast.glsl that
plant_call.sh measured into .old/plant/: 512 FMAs after the sample loop,
their result multiplied by frame.pad_ (0), so the images stay the same.
    python3 lab/2026-12-03_h200_gl_loops/make_variants.py   (from the repository root)"""
import os

src = open("kernels/ssao_alchemy_fast.glsl").read()
anchor = "    float A = pow(max(0.0, 1.0 - P.scale * S), P.contrast);"
assert anchor in src
variants = {
    # one dependent chain in a loop of constant count
    "loop": "    float j = S;\n    for (int k = 0; k < 512; ++k) j = fma(j, 0.9999, 1e-4);\n    S += j * float(frame.pad_);\n",
    # the same chain written out
    "straight": "    float j = S;\n" + "    j = fma(j, 0.9999, 1e-4);\n" * 512 + "    S += j * float(frame.pad_);\n",
    # four independent chains of 128 in a loop
    "vec4": "    vec4 j4 = vec4(S, S + 1.0, S + 2.0, S + 3.0);\n"
            "    for (int k = 0; k < 128; ++k) j4 = fma(j4, vec4(0.9999), vec4(1e-4));\n"
            "    S += dot(j4, vec4(1.0)) * float(frame.pad_);\n",
}
os.makedirs(".old/plant", exist_ok=True)
for name, code in variants.items():
    open(f".old/plant/{name}.glsl", "w").write(src.replace(anchor, code + anchor, 1))
