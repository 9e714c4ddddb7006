// The signed-distance scenes the G-buffer pass ray-marches
// (the SDF AO reference (docs/kernels.md): a scene is a function from a point to the
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
//           them (McGuire et al., HPG 2011's "slatted cabinet"), a back panel
//           behind the recesses, a frame around, standing on a floor.
//   open:    a floor and nothing else: no point of it is occluded, so every
//           AO kernel must give 1 (the SDF AO reference (docs/kernels.md): in open space
//           the distance at height h above the surface is h).
//   contact: a table on four legs with a sphere and a cube resting on its
//           top: the contact darkening where an object meets a surface.
//   grille:  a perforated panel (a grid of 21 x 13 bars, 0.07 holes at a
//           0.1 pitch) in front of a shallow box: regular high-frequency
//           geometry with a cavity behind it.
//   plates:  three stacked discs of shrinking radius on a floor: thin seams
//           where each plate meets the one below.

const int SCENE_CORNER = 0;
const int SCENE_SLATS = 1;
const int SCENE_OPEN = 2;
const int SCENE_CONTACT = 3;
const int SCENE_GRILLE = 4;
const int SCENE_PLATES = 5;

const int MAT_FLOOR = 0;
const int MAT_WALL_X = 1;     // corner: the wall on the plane x = 0
const int MAT_WALL_Z = 2;     // corner: the wall on the plane z = 0
const int MAT_SPHERE = 3;
const int MAT_SLAT = 4;
const int MAT_CABINET = 5;    // slats: top, bottom and side panels
const int MAT_BACK = 6;       // slats: the panel behind the recesses
const int MAT_TABLE = 7;      // contact: table top and legs
const int MAT_CUBE = 8;       // contact: the cube on the table
const int MAT_GRILLE = 9;     // grille: the bars of the perforated panel
const int MAT_CAVITY = 10;    // grille: the box behind the panel
const int MAT_PLATE = 11;     // plates

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
    if (material == MAT_BACK) return rgb8(179.0, 153.0, 128.0);
    if (material == MAT_TABLE) return rgb8(150.0, 110.0, 80.0);
    if (material == MAT_CUBE) return rgb8(120.0, 160.0, 200.0);
    if (material == MAT_GRILLE) return rgb8(170.0, 170.0, 175.0);
    if (material == MAT_CAVITY) return rgb8(90.0, 90.0, 100.0);
    return rgb8(225.0, 222.0, 210.0);   // MAT_PLATE
}

// Exact distance to an axis-aligned box.
float sdBox(vec3 p, vec3 center, vec3 halfSize) {
    vec3 q = abs(p - center) - halfSize;
    return length(max(q, 0.0)) + min(max(q.x, max(q.y, q.z)), 0.0);
}

// Exact distance to a vertical (axis +Y) cylinder with flat caps.
float sdCylinder(vec3 p, vec3 center, float radius, float halfHeight) {
    vec3 q = p - center;
    vec2 d = abs(vec2(length(q.xz), q.y)) - vec2(radius, halfHeight);
    return min(max(d.x, d.y), 0.0) + length(max(d, 0.0));
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

vec2 floorScene(vec3 p) {
    return vec2(sdBox(p, vec3(0.0, -0.1, 0.0), vec3(30.0, 0.1, 30.0)), float(MAT_FLOOR));
}

// The table top is at y = 0.78; the sphere (r 0.2) and the cube (half size
// 0.15) rest on it, touching it along a point and a face.
vec2 contactScene(vec3 p) {
    vec2 h = vec2(sdBox(p, vec3(0.0, -0.1, 0.0), vec3(3.0, 0.1, 3.0)), float(MAT_FLOOR));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 0.75, 0.0), vec3(1.0, 0.03, 0.6)), float(MAT_TABLE)));
    vec3 leg = vec3(abs(p.x), p.y, abs(p.z));   // the four legs by symmetry
    h = nearer(h, vec2(sdBox(leg, vec3(0.92, 0.36, 0.52), vec3(0.04, 0.36, 0.04)), float(MAT_TABLE)));
    h = nearer(h, vec2(length(p - vec3(-0.35, 0.98, 0.1)) - 0.2, float(MAT_SPHERE)));
    h = nearer(h, vec2(sdBox(p, vec3(0.3, 0.93, -0.1), vec3(0.15)), float(MAT_CUBE)));
    return h;
}

// The panel spans x in [-1, 1], y in [0.2, 1.4] at z = 0, bars 0.03 wide
// and deep at a 0.1 pitch. As with the slats, the distance to a set of
// identical bars is the distance to the one whose cell holds p (clamped to
// the grid), so it stays exact. At 320x180 a pitch is about 6 pixels.
const float GRILLE_PITCH = 0.1;

vec2 grilleScene(vec3 p) {
    vec2 h = vec2(sdBox(p, vec3(0.0, -0.1, 0.0), vec3(3.0, 0.1, 3.0)), float(MAT_FLOOR));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 0.1, -0.14), vec3(1.1, 0.1, 0.16)), float(MAT_CAVITY)));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 1.45, -0.14), vec3(1.1, 0.05, 0.16)), float(MAT_CAVITY)));
    h = nearer(h, vec2(sdBox(vec3(abs(p.x), p.y, p.z), vec3(1.05, 0.8, -0.14), vec3(0.05, 0.6, 0.16)), float(MAT_CAVITY)));
    h = nearer(h, vec2(sdBox(p, vec3(0.0, 0.8, -0.28), vec3(1.0, 0.6, 0.02)), float(MAT_CAVITY)));
    float i = clamp(floor((p.x + 1.0) / GRILLE_PITCH + 0.5), 0.0, 20.0);
    float j = clamp(floor((p.y - 0.2) / GRILLE_PITCH + 0.5), 0.0, 12.0);
    vec3 column = vec3(p.x - (-1.0 + i * GRILLE_PITCH), p.y, p.z);
    vec3 row = vec3(p.x, p.y - (0.2 + j * GRILLE_PITCH), p.z);
    h = nearer(h, vec2(sdBox(column, vec3(0.0, 0.8, 0.0), vec3(0.015, 0.6, 0.015)), float(MAT_GRILLE)));
    h = nearer(h, vec2(sdBox(row, vec3(0.0), vec3(1.0, 0.015, 0.015)), float(MAT_GRILLE)));
    return h;
}

// Each plate 0.08 thick and 0.08 narrower than the one below it.
vec2 platesScene(vec3 p) {
    vec2 h = vec2(sdBox(p, vec3(0.0, -0.1, 0.0), vec3(3.0, 0.1, 3.0)), float(MAT_FLOOR));
    h = nearer(h, vec2(sdCylinder(p, vec3(0.0, 0.04, 0.0), 0.8, 0.04), float(MAT_PLATE)));
    h = nearer(h, vec2(sdCylinder(p, vec3(0.0, 0.12, 0.0), 0.72, 0.04), float(MAT_PLATE)));
    h = nearer(h, vec2(sdCylinder(p, vec3(0.0, 0.2, 0.0), 0.64, 0.04), float(MAT_PLATE)));
    return h;
}

// CAVITY_CONST_scene: the scene compiled in (KernelDecl::compileTime), so
// that only its branch exists; the uniform says the same.
vec2 sceneDistance(int scene, vec3 p) {
#ifdef CAVITY_CONST_scene
    scene = CAVITY_CONST_scene;
#endif
    if (scene == SCENE_SLATS) return slatsScene(p);
    if (scene == SCENE_OPEN) return floorScene(p);
    if (scene == SCENE_CONTACT) return contactScene(p);
    if (scene == SCENE_GRILLE) return grilleScene(p);
    if (scene == SCENE_PLATES) return platesScene(p);
    return cornerScene(p);
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
    const vec3 openEye[4] = vec3[4](vec3(0.0, 1.0, 3.0), vec3(1.0, 1.0, 3.0), vec3(-1.0, 0.9, 2.8), vec3(0.5, 1.1, 3.2));
    const vec3 openTarget[4] = vec3[4](vec3(0.0), vec3(0.3, 0.0, 0.0), vec3(-0.3, 0.0, 0.0), vec3(0.2, 0.1, 0.0));
    const vec3 contactEye[4] = vec3[4](vec3(1.0, 1.5, 1.9), vec3(-1.0, 1.5, 1.9), vec3(0.3, 1.4, 2.0), vec3(1.6, 1.6, 1.4));
    const vec3 contactTarget[4] = vec3[4](vec3(0.0, 0.85, 0.0), vec3(0.0, 0.85, 0.0), vec3(0.0, 0.85, 0.0), vec3(0.0, 0.85, 0.0));
    const vec3 grilleEye[4] = vec3[4](vec3(0.6, 1.1, 2.0), vec3(-0.6, 1.1, 2.0), vec3(0.0, 0.95, 1.6), vec3(1.2, 1.2, 1.8));
    const vec3 grilleTarget[4] = vec3[4](vec3(0.0, 0.8, 0.0), vec3(0.0, 0.8, 0.0), vec3(0.0, 0.8, 0.0), vec3(0.1, 0.8, 0.0));
    const vec3 platesEye[4] = vec3[4](vec3(1.3, 0.75, 1.5), vec3(-1.3, 0.75, 1.5), vec3(0.0, 0.7, 1.8), vec3(1.7, 0.8, 0.9));
    const vec3 platesTarget[4] = vec3[4](vec3(0.0, 0.12, 0.0), vec3(0.0, 0.12, 0.0), vec3(0.0, 0.12, 0.0), vec3(0.0, 0.12, 0.0));
    int v = clamp(view, 0, 3);
#ifdef CAVITY_CONST_scene
    scene = CAVITY_CONST_scene;
#endif
    if (scene == SCENE_SLATS) { eye = slatsEye[v]; target = slatsTarget[v]; }
    else if (scene == SCENE_OPEN) { eye = openEye[v]; target = openTarget[v]; }
    else if (scene == SCENE_CONTACT) { eye = contactEye[v]; target = contactTarget[v]; }
    else if (scene == SCENE_GRILLE) { eye = grilleEye[v]; target = grilleTarget[v]; }
    else if (scene == SCENE_PLATES) { eye = platesEye[v]; target = platesTarget[v]; }
    else { eye = cornerEye[v]; target = cornerTarget[v]; }
}
