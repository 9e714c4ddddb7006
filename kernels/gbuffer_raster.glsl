// The rasterised G-buffer: the scene's triangles (harness/meshes.cpp, already
// in view space) drawn with hardware depth into the same four targets the
// ray-marched gbuffer_sdf writes, so every AO kernel runs on either.
// Vertices are pulled from a storage buffer by index: no vertex input state,
// identical on both APIs. Compiled twice, with CAVITY_STAGE_VERTEX or
// CAVITY_STAGE_FRAGMENT defined (harness/pass_chain.cpp prepends #version).

layout(std140, binding = 0) uniform Frame {
    mat4 proj;
    mat4 invProj;
    vec4 camera;
    ivec2 size;
    ivec2 srcSize;
    vec2 invSize;
    vec2 pad_;
} frame;

#ifdef CAVITY_STAGE_VERTEX
struct Vertex {
    vec4 position;
    vec4 normal;
    vec4 albedo;
};
layout(std430, binding = 1) readonly buffer Mesh { Vertex vertices[]; };

layout(location = 0) out vec3 viewPosition;
layout(location = 1) out vec3 viewNormal;
layout(location = 2) out vec3 albedo;

void main() {
#ifdef VULKAN
    Vertex v = vertices[gl_VertexIndex];
#else
    Vertex v = vertices[gl_VertexID];
#endif
    viewPosition = v.position.xyz;
    viewNormal = v.normal.xyz;
    albedo = v.albedo.rgb;
    gl_Position = frame.proj * vec4(v.position.xyz, 1.0);
}
#endif

#ifdef CAVITY_STAGE_FRAGMENT
layout(location = 0) in vec3 viewPosition;
layout(location = 1) in vec3 viewNormal;
layout(location = 2) in vec3 albedo;

layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outLinearDepth;

void main() {
    // w = linear depth, as gbuffer_sdf writes it; background stays the clear value 0.
    outPosition = vec4(viewPosition, -viewPosition.z);
    // Interpolated smooth normals shrink between vertices.
    outNormal = vec4(normalize(viewNormal), 0.0);
    outAlbedo = vec4(albedo, 1.0);
    outLinearDepth = vec4(outPosition.w, 0.0, 0.0, 0.0);
}
#endif
