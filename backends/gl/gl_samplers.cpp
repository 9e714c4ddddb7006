#include "gl/gl_samplers.h"

#include "gl/gl_errors.h"

namespace cavity::gpu::gl {

void SamplerCache::release() {
    for (GLuint& sampler : samplers_)
        if (sampler) glDeleteSamplers(1, &sampler);
    samplers_ = {};
}

Result<GLuint> SamplerCache::get(const SamplerState& state) {
    const bool linear = state.filter == Filter::Linear;
    const bool repeat = state.address == Address::Repeat;
    GLuint& sampler = samplers_[(linear ? 4 : 0) + (repeat ? 2 : 0) + (state.mipmaps ? 1 : 0)];
    if (sampler) return sampler;

    // Without mipmaps the minifying filter ignores every level but the base,
    // so images with mip levels still sample level 0 only.
    GLenum minify = linear ? GL_LINEAR : GL_NEAREST;
    if (state.mipmaps) minify = linear ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_NEAREST;
    const GLenum wrap = repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE;
    GLuint created = 0;
    glCreateSamplers(1, &created);
    glSamplerParameteri(created, GL_TEXTURE_MIN_FILTER, GLint(minify));
    glSamplerParameteri(created, GL_TEXTURE_MAG_FILTER, linear ? GL_LINEAR : GL_NEAREST);
    glSamplerParameteri(created, GL_TEXTURE_WRAP_S, GLint(wrap));
    glSamplerParameteri(created, GL_TEXTURE_WRAP_T, GLint(wrap));
    const Status status = checkGl(std::string("glCreateSamplers ") + (linear ? "linear" : "nearest") + "/" +
                                  (repeat ? "repeat" : "clamp") + (state.mipmaps ? "/mipmaps" : ""));
    if (!status.ok()) {
        glDeleteSamplers(1, &created);
        return status.error();
    }
    sampler = created;
    return sampler;
}

}  // namespace cavity::gpu::gl
