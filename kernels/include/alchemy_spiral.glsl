// Alchemy's sample spiral (McGuire et al., HPG 2011), shared by
// ssao_alchemy.glsl and ssao_alchemy_fast.glsl so that both place sample i
// on the same pixel; harness/reference/alchemy_spiral.h is its CPU twin.
//
// h = alpha R / d in the seed is in units of the image plane at unit
// distance; a pixel is 1 / f of that, with f = 0.5 H / tan(fovY / 2) the
// focal length in pixels. So the disc radius of sample i is
// h_px = alpha R f / d = (i + 0.5) * discScale, discScale = R f / (n d).
// portableReciprocal keeps discScale identical on CPU and GPU, because
// floor() turns any difference into a different sample pixel.
float spiralDiscScale(float R, int n, float d) {
    EXACT float focal = 0.5 * float(frame.size.y) * portableReciprocal(frame.camera.y);
    EXACT float discScale = R * focal * portableReciprocal(float(n) * d);
    return discScale;
}

// The pixel of sample i around the pixel whose centre is fragCentre, with
// u the pixel's phase (pixelHash: neighbouring pixels sample different
// offsets, and the blur averages the pattern away); h gets the sample's
// distance in pixels. theta = 2 pi alpha (7n/9) + phi; with
// alpha = (i + 0.5) / n the angle in turns is (i + 0.5) 7/9 + u, whatever n
// is: 7/9 of a turn per sample spreads successive samples evenly round the disc.
ivec2 spiralSample(int i, float u, float discScale, vec2 fragCentre, out float h) {
    EXACT float turns = (float(i) + 0.5) * 0.7777778 + u;
    vec2 dirCS = cosSinTurns(turns);
    EXACT float radius = (float(i) + 0.5) * discScale;
    EXACT vec2 samplePos = fragCentre + dirCS * radius;
    h = radius;
    return ivec2(floor(samplePos));
}
