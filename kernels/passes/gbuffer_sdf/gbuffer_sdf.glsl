// G-buffer of a signed-distance scene by sphere tracing
// (the SDF AO reference (docs/kernels.md)): march each pixel's ray by the scene distance,
// which can never overshoot a surface, until the distance is negligible.
// Writes view-space position (w = linear depth), view-space normal and
// albedo; a ray that misses leaves all three zero, which every later kernel
// reads as background.
#include "include/common.glsl"
#include "include/sdf_scenes.glsl"

// Most rays converge in 10-20 steps; rays that graze an edge or run into
// the sphere's contact wedge need up to about 260 (1920x1080, both scenes).
// A ray that still has not converged after 320 is creeping along a surface
// (open space is crossed in long steps), so it counts as a hit there.
const int MAX_STEPS = 320;
// Relative to the distance travelled, as a pixel's footprint is (6.4e-3 t
// at 180 rows): every hit is within 1/60 of a pixel of the surface, under
// half a millimetre in these scenes and so far under the AO bias (0.01).
const float HIT_EPSILON = 1e-4;
// Central differences over +-1 mm: far below a pixel's footprint (about
// 1.6 cm at 2.5 units and 320x180), so box edges stay crisp, and far above
// float rounding of scene distances near 1.
const float NORMAL_STEP = 1e-3;

vec3 sceneNormal(int scene, vec3 p) {
    vec3 ex = vec3(NORMAL_STEP, 0.0, 0.0);
    vec3 ey = vec3(0.0, NORMAL_STEP, 0.0);
    vec3 ez = vec3(0.0, 0.0, NORMAL_STEP);
    return normalize(vec3(sceneDistance(scene, p + ex).x - sceneDistance(scene, p - ex).x,
                          sceneDistance(scene, p + ey).x - sceneDistance(scene, p - ey).x,
                          sceneDistance(scene, p + ez).x - sceneDistance(scene, p - ez).x));
}

void cavity_main(ivec2 pixel) {
    vec3 eye, target;
    sceneCamera(P.scene, P.view, eye, target);
    // Camera basis in world space: view +X = right, +Y = up, -Z = forward.
    vec3 forward = normalize(target - eye);
    vec3 right = normalize(cross(forward, vec3(0.0, 1.0, 0.0)));
    vec3 up = cross(right, forward);

    vec3 ray = viewRayAt(pixel);
    vec3 dir = normalize(right * ray.x + up * ray.y - forward * ray.z);

    float t = frame.camera.z;   // start at the near plane
    for (int i = 0; i < MAX_STEPS; ++i) {
        float d = sceneDistance(P.scene, eye + dir * t).x;
        if (d < HIT_EPSILON * t) break;
        t += d;
        if (t > frame.camera.w) break;
    }
    if (t > frame.camera.w) {
        write_position(pixel, vec4(0.0));
        write_normal(pixel, vec4(0.0));
        write_albedo(pixel, vec4(0.0));
        write_linear_depth(pixel, vec4(0.0));
        return;
    }

    vec3 p = eye + dir * t;
    vec3 n = sceneNormal(P.scene, p);
    vec3 q = p - eye;
    float depth = dot(q, forward);
    write_position(pixel, vec4(dot(q, right), dot(q, up), -depth, depth));
    write_linear_depth(pixel, vec4(depth, 0.0, 0.0, 0.0));
    write_normal(pixel, vec4(dot(n, right), dot(n, up), -dot(n, forward), 0.0));
    int material = int(sceneDistance(P.scene, p).y);
    write_albedo(pixel, vec4(materialAlbedo(material), 1.0));
}
