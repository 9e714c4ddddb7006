// The signed-distance scenes the G-buffer pass ray-marches
// (001_8103f59163db3ce3.txt: a scene is a function from a point to the
// distance of the nearest surface). World units are metres-ish, +Y up, so
// that the AO radius default R = 0.5 spans a crease or a recess but not the
// whole room. The CPU reference (harness/reference/sdf_scenes.cpp) holds the
// same numbers; change both together.
//
//   corner: a floor and two walls meeting at right angles at the origin,
//           walls on the planes x = 0 and z = 0, and a sphere resting on the
//           floor near the crease: floor contact, wall-floor creases, the
//           three-way corner and a sphere-to-wall gap.
//   slats:  a cabinet front of 30 thin vertical slats with recesses between
//           them (000_79d41de70034b569.txt's "slatted cabinet"), a back panel
//           behind the recesses, a frame around, standing on a floor.

const int SCENE_CORNER = 0;
const int SCENE_SLATS = 1;

const int MAT_FLOOR = 0;
const int MAT_WALL_X = 1;     // corner: the wall on the plane x = 0
const int MAT_WALL_Z = 2;     // corner: the wall on the plane z = 0
const int MAT_SPHERE = 3;
const int MAT_SLAT = 4;
const int MAT_CABINET = 5;    // slats: top, bottom and side panels
const int MAT_BACK = 6;       // slats: the panel behind the recesses

// Albedo is stored in RGBA8, so it is given in 8-bit steps: k / 255 times
// 255 lands within float rounding of the integer k, never near a .5 that
// one implementation would round up and another down.
vec3 rgb8(float r, float g, float b) {
    return vec3(r, g, b) / 255.0;
}

vec3 materialAlbedo(int material) {
    if (material == MAT_FLOOR) return rgb8(158.0, 153.0, 143.0);
    if (material == MAT_WALL_X) return rgb8(204.0, 143.0, 117.0);
    if (material == MAT_WALL_Z) return rgb8(143.0, 173.0, 204.0);
    if (material == MAT_SPHERE) return rgb8(235.0, 235.0, 230.0);
    if (material == MAT_SLAT) return rgb8(194.0, 148.0, 102.0);
    if (material == MAT_CABINET) return rgb8(143.0, 102.0, 69.0);
    return rgb8(179.0, 153.0, 128.0);   // MAT_BACK
}

// Exact distance to an axis-aligned box.
float sdBox(vec3 p, vec3 center, vec3 halfSize) {
    vec3 q = abs(p - center) - halfSize;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// The nearer of two (distance, material) pairs: a union that remembers
// which part was hit.
vec2 nearer(vec2 a, vec2 b) {
    return b.x < a.x ? b : a;
}

const vec3 CORNER_SPHERE_CENTER = vec3(0.8, 0.5, 1.6);
const float CORNER_SPHERE_RADIUS = 0.5;

vec2 cornerScene(vec3 p) {
    // Walls and floor overlap below y = 0 and behind the planes, so the
    // creases are solid and the distance near them is exact.
    vec2 h = vec2(sdBox(p, vec3(1.9, -0.1, 1.9), vec3(2.1, 0.1, 2.1)), float(MAT_FLOOR));
    h = nearer(h, vec2(sdBox(p, vec3(-0.1, 0.9, 1.9), vec3(0.1, 1.1, 2.1)), float(MAT_WALL_X)));
    h = nearer(h, vec2(sdBox(p, vec3(1.9, 0.9, -0.1), vec3(2.1, 1.1, 0.1)), float(MAT_WALL_Z)));
    h = nearer(h, vec2(length(p - CORNER_SPHERE_CENTER) - CORNER_SPHERE_RADIUS, float(MAT_SPHERE)));
    return h;
}

// 30 slats at a 0.12 pitch fill x in [-1.8, 1.8], 1.9 tall: 0.05 thick
// with 0.07 recesses between them, 0.18 deep, and 0.16 of open space behind
// them before the back panel. The recesses are narrow against R = 0.5, so
// their sides and the panel behind are strongly occluded while the slat
// fronts stay open. The cabinet's 3.7 x 2.1 front is close to 16:9, so it
// fills the frame; at 320x180 a slat and a recess are 4-5 pixels each.
const int SLAT_COUNT = 30;
const float SLAT_PITCH = 0.12;

vec2 slatsScene(vec3 p) {
    vec2 h = vec2(sdBox(p, vec3(0.0, -0.1, 0.0), vec3(3.0, 0.1, 2.5)), float(MAT_FLOOR));
    // Bottom, top and sides stand 0.06 proud of the slat fronts (z = 0).
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 0.06, -0.17), vec3(1.86, 0.06, 0.23)), float(MAT_CABINET)));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 2.08, -0.17), vec3(1.86, 0.06, 0.23)), float(MAT_CABINET)));
    h = nearer(h, vec2(sdBox(p, vec3(-1.83, 1.07, -0.17), vec3(0.03, 1.07, 0.23)), float(MAT_CABINET)));
    h = nearer(h, vec2(sdBox(p, vec3(1.83, 1.07, -0.17), vec3(0.03, 1.07, 0.23)), float(MAT_CABINET)));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 1.07, -0.37), vec3(1.80, 0.95, 0.03)), float(MAT_BACK)));
    // Domain repetition: measure against the slat of the pitch cell that
    // holds p.x, clamped to the 30 cells. Each slat is centred in its cell,
    // so no neighbour is ever nearer and the distance stays exact.
    float cell = clamp(floor(p.x / SLAT_PITCH), -float(SLAT_COUNT / 2), float(SLAT_COUNT / 2 - 1));
    vec3 local = vec3(p.x - (cell + 0.5) * SLAT_PITCH, p.y, p.z);
    h = nearer(h, vec2(sdBox(local, vec3(0.0, 1.07, -0.09), vec3(0.025, 0.95, 0.09)), float(MAT_SLAT)));
    return h;
}

vec2 sceneDistance(int scene, vec3 p) {
    return scene == SCENE_SLATS ? slatsScene(p) : cornerScene(p);
}

// Four camera poses per scene (the `view` parameter), so that a benchmark
// can rotate between inputs. All look roughly level (pitch under 20
// degrees), which the composite's sky term relies on.
void sceneCamera(int scene, int view, out vec3 eye, out vec3 target) {
    const vec3 cornerEye[4] = vec3[4](vec3(2.7, 1.3, 2.8), vec3(3.1, 1.25, 2.1), vec3(2.0, 1.25, 3.2), vec3(2.5, 1.1, 2.5));
    const vec3 cornerTarget[4] = vec3[4](vec3(0.5, 0.45, 0.6), vec3(0.6, 0.45, 0.7), vec3(0.5, 0.45, 0.8), vec3(0.45, 0.4, 0.55));
    // Every slats eye sits at a recess centre in x (a multiple of the
    // pitch): the rays that run parallel to the slat sides then pass down
    // the middle of a recess instead of creeping along a side at a tiny
    // step for hundreds of steps.
    const vec3 slatsEye[4] = vec3[4](vec3(0.72, 1.25, 2.3), vec3(-0.72, 1.25, 2.3), vec3(0.36, 1.05, 2.2), vec3(1.08, 1.5, 2.25));
    const vec3 slatsTarget[4] = vec3[4](vec3(0.05, 1.0, -0.1), vec3(-0.05, 1.0, -0.1), vec3(0.0, 1.0, -0.1), vec3(0.1, 1.0, -0.1));
    int v = clamp(view, 0, 3);
    eye = scene == SCENE_SLATS ? slatsEye[v] : cornerEye[v];
    target = scene == SCENE_SLATS ? slatsTarget[v] : cornerTarget[v];
}
