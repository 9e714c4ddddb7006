// One axis of the separable depth-aware blur of the fast AO pipelines
// (blur_separable_x.glsl, then blur_separable_y.glsl). Each pass reads one
// RGBA16F texel per tap, AO, linear depth and the octahedral normal packed
// together (after Scalable Ambient Obscurance, which packs AO and depth):
// 2 (2r + 1) fetches in all, against the (2r + 1)^2 taps of three images each
// of blur_bilateral.glsl.
//
// Each tap is weighted as blur_bilateral.glsl weighs it: the 1-D Gaussian
// (the same weights, so r and sigma = r / 2 mean the same), times the normal
// agreement max(0, N . Ni), times exp(-dd^2 / (2 sigma_d^2)) in depth; the
// weight rejected goes back to the centre, so nothing crosses a silhouette
// or a crease. An earlier key of AO and depth alone (32 bits, no normal)
// blurred the slats' creases together: 0.122 MAE against the truth where the
// 2-D blur gives 0.091 (lavapipe, 640x360). What the two passes still cannot
// do: a diagonal tap is weighed by way of the pixel the first pass met, not
// against the centre directly.
#include "include/common.glsl"
#include "include/octahedral.glsl"

float gaussianWeight(int i) {
    return P.weights[i >> 2][i & 3];
}

// What the kernel blurs beside the key's AO, with the same weights, at
// texel q: the SSDO radiance (blur_separable_ssdo_x.glsl), or vec3(0.0)
// where there is nothing. Each kernel defines it, and before including this
// defines BLUR_WITH when there is something, and BLUR_WITH_IN_TILE as well
// when the tile is to hold it.
vec3 blurredWith(ivec2 q);

// The axis: each kernel defines BLUR_ALONG_X, or not, before including this.
#ifdef BLUR_ALONG_X
const ivec2 kBlurAxis = ivec2(1, 0);
#else
const ivec2 kBlurAxis = ivec2(0, 1);
#endif

float tapWeight(int t, vec3 N, vec3 tapNormal, float dd, float twoSigma2) {
    return gaussianWeight(abs(t)) * max(0.0, dot(N, tapNormal)) * exp(-dd * dd / twoSigma2);
}

// The compute pass's tile: the workgroup's pixels and the r texels either
// side along the axis, each decoded once (normal, linear depth, AO) where
// each tap decoded its own, 2r + 1 times a texel; a texel past the image's
// edge has depth 0, so it is skipped as background, as the texture path
// skips it. The kernel declares wholeWorkgroups (every invocation loads and
// meets at the barrier) and compiles its radius in, which sizes the tile
// and writes the taps out. The tile keeps to 768 texels, 15 KiB, under the
// 16 KiB of shared memory every Vulkan device has: every radius (1 to 32)
// in the declared workgroups, 64x4 along x and 4x64 along y, which run the
// tile long along the axis. With BLUR_WITH_IN_TILE a texel takes 12 bytes
// more (the radiance, fetched once where every tap fetched it), and the
// tile keeps to 512 texels, 16 KiB, which still holds every radius in those
// shapes.
// ssdo_fast's horizontal pass tiles its radiance so, which made it faster on
// the H200's Vulkan and no slower on GL; its vertical pass, whose taps fetch
// down a column, got slower on Vulkan that way and fetches its radiance a
// tap (study 2026-12-04_h200_floors).
// A shape that overflows it (CAVITY_WORKGROUP), and the fragment stage,
// take the texture path.
#if defined(CAVITY_STAGE_COMPUTE) && defined(CAVITY_CONST_blur)
#ifdef BLUR_ALONG_X
#define BLUR_TILE_TEXELS ((CAVITY_WORKGROUP_X + 2 * CAVITY_CONST_blur) * CAVITY_WORKGROUP_Y)
#else
#define BLUR_TILE_TEXELS ((CAVITY_WORKGROUP_Y + 2 * CAVITY_CONST_blur) * CAVITY_WORKGROUP_X)
#endif
#ifdef BLUR_WITH_IN_TILE
#define BLUR_TILE_LIMIT 512
#else
#define BLUR_TILE_LIMIT 768
#endif
#if CAVITY_CONST_blur >= 1 && BLUR_TILE_TEXELS <= BLUR_TILE_LIMIT
#define BLUR_TILED 1
const int kTileW = CAVITY_WORKGROUP_X + 2 * CAVITY_CONST_blur * kBlurAxis.x;
const int kTileH = CAVITY_WORKGROUP_Y + 2 * CAVITY_CONST_blur * kBlurAxis.y;
shared vec4 tileNormalDepth[kTileW * kTileH];
shared float tileAo[kTileW * kTileH];
#ifdef BLUR_WITH_IN_TILE
shared float tileWithR[kTileW * kTileH], tileWithG[kTileW * kTileH], tileWithB[kTileW * kTileH];
#endif
#endif
#endif

// Every invocation of the workgroup calls this first, also those past the
// image's edge; it does nothing where there is no tile.
void blurShareTile() {
#ifdef BLUR_TILED
    ivec2 origin = ivec2(gl_WorkGroupID.xy) * ivec2(CAVITY_WORKGROUP_X, CAVITY_WORKGROUP_Y) - kBlurAxis * CAVITY_CONST_blur;
    for (int i = int(gl_LocalInvocationIndex); i < kTileW * kTileH; i += CAVITY_WORKGROUP_X * CAVITY_WORKGROUP_Y) {
        ivec2 q = origin + ivec2(i % kTileW, i / kTileW);
        vec4 key = inImage(q) ? texelFetch(in_ao_key, q, 0) : vec4(0.0);
        tileNormalDepth[i] = vec4(octDecode(key.ba), key.g);
        tileAo[i] = key.r;
#ifdef BLUR_WITH_IN_TILE
        vec3 beside = inImage(q) ? blurredWith(q) : vec3(0.0);
        tileWithR[i] = beside.r;
        tileWithG[i] = beside.g;
        tileWithB[i] = beside.b;
#endif
    }
    barrier();
#endif
}

// The running sums of blurAlong().
struct BlurSums {
    float ao;
    vec3 value;
    float weight;
};

#ifdef BLUR_TILED
// Tap t, tile texel i, of the centre `pixel` (normal N, linear depth z). A
// background tap weighs 0, chosen by a select rather than a branch around
// the tap: each pass was faster so on the H200, with the same sums (0 added;
// study 2026-12-04_h200_floors).
void addTileTap(int t, int i, ivec2 pixel, vec3 N, float z, float twoSigma2, inout BlurSums s) {
    vec4 tap = tileNormalDepth[i];
    bool counts = !isBackground(tap.w);
    float W = tapWeight(t, N, tap.xyz, z - tap.w, twoSigma2);
    W = counts ? W : 0.0;
    s.ao += tileAo[i] * W;
#if defined(BLUR_WITH_IN_TILE)
    s.value += vec3(tileWithR[i], tileWithG[i], tileWithB[i]) * W;
#elif defined(BLUR_WITH)
    // Fetched only for a tap that counts: a background one may lie past the
    // image's edge.
    if (counts) s.value += blurredWith(pixel + kBlurAxis * t) * W;
#endif
    s.weight += W;
}
#endif

// The centre's key with its AO blurred along the axis, and in `value` what
// blurredWith() reads, blurred alike. Call blurShareTile() before.
vec4 blurAlong(ivec2 pixel, out vec3 value) {
    vec4 centre = texelFetch(in_ao_key, pixel, 0);
    value = blurredWith(pixel);
    int r = P.blur;
    if (r == 0 || isBackground(centre.g)) return centre;
    float twoSigma2 = 2.0 * P.depth_sigma * P.depth_sigma;
    BlurSums s = BlurSums(0.0, vec3(0.0), 0.0);
#ifdef BLUR_TILED
    // The taps written out, -r to r in the loop's order (the same sums):
    // NVIDIA's GL driver keeps a loop of constant count rolled, and written
    // out the pass took much less time there and no more on Vulkan
    // (study 2026-12-03_h200_blur_tile).
    ivec2 local = ivec2(gl_LocalInvocationID.xy) + kBlurAxis * CAVITY_CONST_blur;
    int c = local.y * kTileW + local.x;
    int stride = kBlurAxis.x + kBlurAxis.y * kTileW;
    vec3 N = tileNormalDepth[c].xyz;
#define BLUR_TAP(t) addTileTap(t, c + (t) * stride, pixel, N, centre.g, twoSigma2, s);
#define BLUR_TAP_BELOW(i) BLUR_TAP(i - CAVITY_CONST_blur)
#define BLUR_TAP_ABOVE(i) BLUR_TAP(i + 1)
    CAVITY_REPEAT_blur(BLUR_TAP_BELOW) BLUR_TAP(0) CAVITY_REPEAT_blur(BLUR_TAP_ABOVE)
#else
    vec3 N = octDecode(centre.ba);
    for (int t = -r; t <= r; ++t) {
        ivec2 q = pixel + kBlurAxis * t;
        if (!inImage(q)) continue;
        vec4 tap = texelFetch(in_ao_key, q, 0);
        if (isBackground(tap.g)) continue;
        float W = tapWeight(t, N, octDecode(tap.ba), centre.g - tap.g, twoSigma2);
        s.ao += tap.r * W;
        s.value += blurredWith(q) * W;
        s.weight += W;
    }
#endif
    value = s.value + (1.0 - s.weight) * value;
    return vec4(s.ao + (1.0 - s.weight) * centre.r, centre.gba);
}
