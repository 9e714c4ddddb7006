// Per-pixel noise, seeded only by the pixel position: the same frame gives
// the same image every run and on every backend, and the CPU references
// (harness/reference/noise.h) reproduce it bit for bit. Integers wrap the
// same everywhere, and the float conversions below are exact.

// PCG hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", 2020):
// one round of a PCG generator with an output permutation; cheap and with
// no visible structure between neighbouring inputs.
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The top 24 bits as a float in [0, 1): a 24-bit integer and a power-of-two
// scale are both exact in float, so the CPU gets the same value.
float hashToUnit(uint h) {
    return float(h >> 8u) * (1.0 / 16777216.0);
}

// A hash of the pixel position. 65521 (a prime just under 2^16) keeps
// distinct pixels of any image up to 16384 wide on distinct seeds.
float pixelHash(ivec2 pixel) {
    return hashToUnit(pcgHash(uint(pixel.x) + uint(pixel.y) * 65521u));
}

// The pixel that seeds a pixel's per-pixel randomness: itself, or with
// interleaved layers (CAVITY_INTERLEAVE k > 1, KernelDecl::interleaved) its
// layer pixel % k, which every pixel of that layer shares: a workgroup of
// the interleaved dispatch then puts its samples at one offset from each of
// its pixels, and its fetches move through the layer together.
ivec2 phasePixel(ivec2 pixel) {
#if defined(CAVITY_INTERLEAVE) && CAVITY_INTERLEAVE > 1
    return pixel % CAVITY_INTERLEAVE;
#else
    return pixel;
#endif
}

// A pixel's sample phase in turns: its hash, or its layer's. The k x k
// layers' phases are evenly spaced, (7 i mod k^2) / k^2 for layer
// i = l.y k + l.x, so that any k x k block of pixels, which the blur
// averages, holds every phase once. Exact in float for k = 2 and 4.
float samplePhase(ivec2 pixel) {
#if defined(CAVITY_INTERLEAVE) && CAVITY_INTERLEAVE > 1
    ivec2 l = phasePixel(pixel);
    const int n = CAVITY_INTERLEAVE * CAVITY_INTERLEAVE;
    return float((l.y * CAVITY_INTERLEAVE + l.x) * 7 % n) * (1.0 / float(n));
#else
    return pixelHash(pixel);
#endif
}

// Interleaved gradient noise (Jimenez 2014; the hemisphere SSAO lesson (docs/kernels.md)):
// values in [0, 1) that differ strongly between neighbouring pixels yet are
// well spread over any small block, so a +-half-step dither built from it
// breaks up 8-bit bands without looking like grain. `p` is a pixel centre.
float ign(vec2 p) {
    EXACT float inner = 0.06711056 * p.x + 0.00583715 * p.y;
    EXACT float outer = 52.982918 * (inner - floor(inner));
    return outer - floor(outer);
}
