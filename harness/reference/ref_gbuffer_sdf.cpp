// Reference of kernels/passes/gbuffer_sdf/gbuffer_sdf.glsl: the same sphere trace, step for
// step. It cannot match the GPU bit for bit (length(), normalize() and the
// scene's divisions are not exactly rounded on GPUs), so a ray grazing a
// silhouette may hit on one side and miss on the other; interior pixels
// agree to the hit tolerance (1e-4 of the distance).
#include "reference/refs.h"
#include "reference/sdf_scenes.h"

#include <algorithm>

namespace cavity::reference {

namespace {

const int kMaxSteps = 320;
const float kHitEpsilon = 1e-4f;
const float kNormalStep = 1e-3f;

Vec3 sceneNormal(Scene scene, Vec3 p) {
    const Vec3 ex{kNormalStep, 0, 0}, ey{0, kNormalStep, 0}, ez{0, 0, kNormalStep};
    return normalize(Vec3{sceneDistance(scene, p + ex).distance - sceneDistance(scene, p - ex).distance,
                          sceneDistance(scene, p + ey).distance - sceneDistance(scene, p - ey).distance,
                          sceneDistance(scene, p + ez).distance - sceneDistance(scene, p - ez).distance});
}

}  // namespace

Result<std::vector<HostImage>> gbufferSdf(const Context& ctx) {
    const auto& f = ctx.frame;
    const Scene scene = Scene(std::clamp(intParam(ctx, "scene"), 0, kSceneCount - 1));
    const CameraPose pose = sceneCamera(scene, intParam(ctx, "view"));
    const Vec3 forward = normalize(pose.target - pose.eye);
    const Vec3 right = normalize(cross(forward, Vec3{0, 1, 0}));
    const Vec3 up = cross(right, forward);

    auto out = makeOutputs(ctx);
    HostImage& position = out[0];
    HostImage& normal = out[1];
    HostImage& albedo = out[2];
    HostImage& linearDepth = out[3];
    for (int y = 0; y < f.size[1]; ++y) {
        for (int x = 0; x < f.size[0]; ++x) {
            // viewRayAt (common.glsl): row 0 is the top, +Y up.
            const float ndcX = (float(x) + 0.5f) * f.invSize[0] * 2.0f - 1.0f;
            const float ndcY = (float(y) + 0.5f) * f.invSize[1] * 2.0f - 1.0f;
            const Vec3 ray{ndcX * f.camera[0], -ndcY * f.camera[1], -1.0f};
            const Vec3 dir = normalize(right * ray.x + up * ray.y - forward * ray.z);

            float t = f.camera[2];
            for (int i = 0; i < kMaxSteps; ++i) {
                const float d = sceneDistance(scene, pose.eye + dir * t).distance;
                if (d < kHitEpsilon * t) break;
                t += d;
                if (t > f.camera[3]) break;
            }
            // Out of steps but not past far: creeping along a surface, a hit.
            if (t > f.camera[3]) continue;   // missed: outputs stay zero, background

            const Vec3 p = pose.eye + dir * t;
            const Vec3 n = sceneNormal(scene, p);
            const Vec3 q = p - pose.eye;
            const float depth = dot(q, forward);
            const float pos[4] = {dot(q, right), dot(q, up), -depth, depth};
            const float nrm[4] = {dot(n, right), dot(n, up), -dot(n, forward), 0.0f};
            const Vec3 a = materialAlbedo(sceneDistance(scene, p).material);
            const float alb[4] = {a.x, a.y, a.z, 1.0f};
            for (int c = 0; c < 4; ++c) {
                position.at(x, y, c) = pos[c];
                normal.at(x, y, c) = nrm[c];
                albedo.at(x, y, c) = alb[c];
            }
            linearDepth.at(x, y) = depth;
        }
    }
    return out;
}

}  // namespace cavity::reference
