// Screen-space directional occlusion on the linear-depth pyramid: the direct
// pass of ssdo_marched (ssdo_direct.glsl, seed Ritschel et al., I3D 2009, each
// direction marched in `steps` points out to R) with each point tested by
// one RG32F fetch of the pyramid along the receiver's normal
// (include/ssdo_fast.glsl), where ssdo_direct.glsl fetches an RGBA32F
// position and an RGBA16F normal per point. The sky is gathered as there.
//
// Besides visibility and radiance it writes the separable blur's key
// (visibility, linear depth, octahedral normal), as the fast AO kernels do;
// the blur pair carries the radiance along with the same weights
// (blur_separable_ssdo_x.glsl).
#include "include/ssdo_fast.glsl"
#include "include/octahedral.glsl"

// The sky over the receiver's directions. Called with r.view, or with
// belowTiny(r.view) where every level is below the tiny ones: that copy,
// with a constant there, tests nothing more per point (include/pyramid.glsl).
SkyGather gatherDirections(FastReceiver r, ivec2 pixel) {
    SkyGather g = SkyGather(0.0, 0.0, vec3(0.0));
    for (int i = 0; i < r.count; ++i) {
        FastSample s = fastSample(r, pixel, i);
        gatherSky(g, r.n, s.dir, textureLod(in_sky, skyUv(s.dir), P.sky_lod).rgb, s.visible);
    }
    return g;
}

void cavity_main(ivec2 pixel) {
    FastReceiver r;
    if (!fastReceiver(pixel, r)) {
        // Background: open, and its radiance is the sky seen through the
        // pixel, for the composite to show.
        vec3 ray = normalize(viewRayAt(pixel));
        write_visibility(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        write_radiance(pixel, vec4(textureLod(in_sky, skyUv(ray), 0.0).rgb, 1.0));
        write_ao_key(pixel, vec4(1.0, 0.0, 0.0, 0.0));
        return;
    }
    SkyGather g;
    if (r.view.maxLevel < r.view.tiny) {
        r.view = belowTiny(r.view);
        g = gatherDirections(r, pixel);
    } else {
        g = gatherDirections(r, pixel);
    }
    float visibility = skyVisibility(g, P.contrast);
    write_visibility(pixel, vec4(visibility, 0.0, 0.0, 0.0));
    write_radiance(pixel, vec4(skyRadiance(g, r.count), 1.0));
    write_ao_key(pixel, vec4(visibility, r.depth, octEncode(r.n)));
}
