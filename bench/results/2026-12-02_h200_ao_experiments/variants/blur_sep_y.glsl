#include "include/common.glsl"
#include "include/octahedral.glsl"
// EXPERIMENT: one 8x8 group loads its row (or column) span once into shared memory.
const int MAX_R = 4;
const int SPAN = 8 + 2 * MAX_R;
shared vec4 sKey[8][SPAN];   // ao, depth, n.x, n.y
shared float sNz[8][SPAN];

float gaussianWeight(int i) { return P.weights[i >> 2][i & 3]; }

vec4 blurTiled(ivec2 pixel, ivec2 axis) {
    ivec2 lid = ivec2(gl_LocalInvocationID.xy);
    ivec2 base = ivec2(gl_WorkGroupID.xy) * 8;
    int r = min(P.blur, MAX_R);
    int W = 8 + 2 * r;
    ivec2 cross_ = ivec2(1, 1) - axis;
    for (int idx = lid.y * 8 + lid.x; idx < W * 8; idx += 64) {
        int line = idx / W, col = idx % W;
        ivec2 q = base + axis * (col - r) + cross_ * line;
        vec4 key = vec4(0.0);
        if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, frame.size))) key = texelFetch(in_ao_key, q, 0);
        vec3 n = octDecode(key.ba);
        sKey[line][col] = vec4(key.r, key.g, n.x, n.y);
        sNz[line][col] = n.z;
    }
    barrier();
    vec4 centre = texelFetch(in_ao_key, pixel, 0);
    if (r == 0 || isBackground(centre.g)) return centre;
    int line = axis.x == 1 ? lid.y : lid.x;
    int at = (axis.x == 1 ? lid.x : lid.y) + r;
    vec3 N = vec3(sKey[line][at].zw, sNz[line][at]);
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
    float sum = 0.0, totalWeight = 0.0;
    for (int t = -r; t <= r; ++t) {
        vec4 tap = sKey[line][at + t];
        if (isBackground(tap.g)) continue;
        float dd = centre.g - tap.g;
        float W = gaussianWeight(abs(t)) * max(0.0, dot(N, vec3(tap.zw, sNz[line][at + t]))) * exp(-dd * dd / twoSigma2);
        sum += tap.r * W;
        totalWeight += W;
    }
    return vec4(sum + (1.0 - totalWeight) * centre.r, centre.gba);
}
void cavity_main(ivec2 pixel) { write_ao(pixel, vec4(blurTiled(pixel, ivec2(0, 1)).r, 0.0, 0.0, 0.0)); }
