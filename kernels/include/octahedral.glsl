// A unit normal in two numbers (octahedral encoding): the normal projected
// onto the octahedron |x| + |y| + |z| = 1, the lower half folded over the
// upper. Two half floats keep it to about 1e-3, enough for a blur's normal
// weight, and leave room beside AO and depth in one RGBA16F texel.
vec2 octEncode(vec3 n) {
    vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
    if (n.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
    return p;
}

vec3 octDecode(vec2 p) {
    vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    return normalize(n);
}
