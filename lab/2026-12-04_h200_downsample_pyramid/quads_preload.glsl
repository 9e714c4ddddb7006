// The fused half-resolution tail: the joint bilateral upsample
// (include/upsample.glsl) and the composite (include/composite.glsl) in one
// full-resolution pass, so that a half-resolution frame pays one pass, one
// read of the full-resolution normal and position, and no round trip of the
// full-resolution AO through memory before the composite reads it. It still
// writes that AO (write_ao) for the gate and the quality measure.
//
// The stored AO is upsample_bilateral's, bit for bit. The colour is
// composited from the AO before the R16F store rounds it, so it may differ
// from the two passes' by one 8-bit step where the rounding crosses one
// (a test checks both on both APIs). Rounding it first to match cannot be
// exact: packHalf2x16 rounds to nearest, while an R16F store may round
// towards zero (lavapipe's does: one half-float step on a quarter of the
// pixels).
#include "include/upsample.glsl"
#include "include/composite.glsl"

// A pixel inside the image: its upsampled AO and its colour.
void shadeTail(ivec2 pixel, out float ao, out vec4 color) {
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    ao = 1.0;
    if (!isBackground(p.w) && lengthSquared(nrm) != 0.0)
        ao = upsampleAo(pixel, p, nrm);
    color = compositeColor(pixel, albedo, nrm, ao);
}

#ifdef CAVITY_QUADS
// Variant: the quad's 3x3 half texels fetched once into registers.
float aoHalf[9];
vec4 qHalf[9];
vec3 mHalf[9];

float upsampleFromBlock(ivec2 pixel, ivec2 blockBase, vec4 p, vec3 nrm) {
    vec2 c = vec2(pixel) * 0.5 - 0.25;
    ivec2 base = ivec2(floor(c));
    vec2 f = c - vec2(base);
    float tol = P.upsample_depth_tolerance * p.w;
    float sum = 0.0, weightSum = 0.0;
    float fallback = 1.0, fallbackDist = 3.0e38;
    for (int k = 0; k < 4; ++k) {
        ivec2 o = ivec2(k & 1, k >> 1);
        ivec2 t = base + o - blockBase;
        int i = t.y * 3 + t.x;
        float ao = aoHalf[i];
        vec4 q = qHalf[i];
        vec3 m = mHalf[i];
        if (isBackground(q.w)) continue;
        float bilinear = (o.x == 1 ? f.x : 1.0 - f.x) * (o.y == 1 ? f.y : 1.0 - f.y);
        float planeDist = abs(orderedDot(nrm, q.xyz - p.xyz)) / tol;
        float depthWeight = exp(-0.5 * planeDist * planeDist);
        float cn = max(orderedDot(nrm, m), 0.0);
        cn *= cn;
        cn *= cn;
        float normalWeight = cn * cn;
        float w = bilinear * depthWeight * normalWeight;
        sum += w * ao;
        weightSum += w;
        float dz = abs(q.w - p.w);
        if (dz < fallbackDist) {
            fallbackDist = dz;
            fallback = ao;
        }
    }
    return weightSum > 1e-5 ? sum / weightSum : fallback;
}

void shadeQuadPixel(ivec2 pixel, ivec2 blockBase, out float ao, out vec4 color) {
    vec4 albedo = texelFetch(in_albedo, pixel, 0);
    vec4 p = texelFetch(in_position, pixel, 0);
    vec3 nrm = texelFetch(in_normal, pixel, 0).xyz;
    ao = 1.0;
    if (!isBackground(p.w) && lengthSquared(nrm) != 0.0)
        ao = upsampleFromBlock(pixel, blockBase, p, nrm);
    color = compositeColor(pixel, albedo, nrm, ao);
}

void cavity_main(ivec2 quad) {
    ivec2 halfSize = textureSize(in_ao_half, 0);
    ivec2 blockBase = quad / 2 - 1;
    for (int i = 0; i < 9; ++i) {
        ivec2 texel = clamp(blockBase + ivec2(i % 3, i / 3), ivec2(0), halfSize - 1);
        aoHalf[i] = texelFetch(in_ao_half, texel, 0).r;
        qHalf[i] = texelFetch(in_position_half, texel, 0);
        mHalf[i] = texelFetch(in_normal_half, texel, 0).xyz;
    }
    ivec2 last = frame.size - 1;
    ivec2 p0 = quad, p1 = min(quad + ivec2(1, 0), last), p2 = min(quad + ivec2(0, 1), last), p3 = min(quad + 1, last);
    float a0, a1, a2, a3;
    vec4 c0, c1, c2, c3;
    shadeQuadPixel(p0, blockBase, a0, c0);
    shadeQuadPixel(p1, blockBase, a1, c1);
    shadeQuadPixel(p2, blockBase, a2, c2);
    shadeQuadPixel(p3, blockBase, a3, c3);
    write_ao(p0, vec4(a0, 0.0, 0.0, 0.0));
    write_color(p0, c0);
    if (quad.x < last.x) {
        write_ao(p1, vec4(a1, 0.0, 0.0, 0.0));
        write_color(p1, c1);
    }
    if (quad.y < last.y) {
        write_ao(p2, vec4(a2, 0.0, 0.0, 0.0));
        write_color(p2, c2);
    }
    if (quad.x < last.x && quad.y < last.y) {
        write_ao(p3, vec4(a3, 0.0, 0.0, 0.0));
        write_color(p3, c3);
    }
}
#else
void cavity_main(ivec2 pixel) {
    upsampleShareTile();
    if (!inImage(pixel)) return;
    float ao;
    vec4 color;
    shadeTail(pixel, ao, color);
    write_ao(pixel, vec4(ao, 0.0, 0.0, 0.0));
    write_color(pixel, color);
}
#endif
