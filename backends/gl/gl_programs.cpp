#include "gl/gl_programs.h"

#include "compiler.h"
#include "gl/gl_errors.h"

#include <cctype>
#include <optional>
#include <vector>

namespace cavity::gpu::gl {
namespace {

GLenum shaderType(Stage stage) {
    switch (stage) {
    case Stage::Compute: return GL_COMPUTE_SHADER;
    case Stage::Vertex: return GL_VERTEX_SHADER;
    case Stage::Fragment: return GL_FRAGMENT_SHADER;
    }
    return GL_COMPUTE_SHADER;
}

const char* stageName(Stage stage) {
    switch (stage) {
    case Stage::Compute: return "compute";
    case Stage::Vertex: return "vertex";
    case Stage::Fragment: return "fragment";
    }
    return "?";
}

std::string shaderLog(GLuint shader) {
    GLint length = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(length > 0 ? length : 0), '\0');
    if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log.empty() ? "(no log)" : log;
}

std::string programLog(GLuint program) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(length > 0 ? length : 0), '\0');
    if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    return log.empty() ? "(no log)" : log;
}

// Shader objects are only needed until the program is linked.
struct Shaders {
    std::vector<GLuint> ids;
    ~Shaders() {
        for (GLuint id : ids) glDeleteShader(id);
    }
};

std::string who(const ShaderSource& s) { return s.name + " (" + stageName(s.stage) + ")"; }

Result<GLuint> createShader(const ShaderSource& source, Shaders& shaders) {
    const GLuint shader = glCreateShader(shaderType(source.stage));
    CAVITY_TRY(checkGl("glCreateShader " + who(source)));
    if (shader == 0) return internal("gl: glCreateShader " + who(source) + " returned 0");
    shaders.ids.push_back(shader);
    return shader;
}

bool compiled(GLuint shader) {
    GLint ok = GL_FALSE;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    return ok == GL_TRUE;
}

Result<GLuint> link(const Shaders& shaders, const ShaderSource& first) {
    const GLuint program = glCreateProgram();
    CAVITY_TRY(checkGl("glCreateProgram " + first.name));
    for (GLuint shader : shaders.ids) glAttachShader(program, shader);
    glLinkProgram(program);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    for (GLuint shader : shaders.ids) glDetachShader(program, shader);
    Status status = checkGl("glLinkProgram " + first.name);
    if (status.ok() && ok != GL_TRUE) status = internal("gl: link " + first.name + ": " + oneLine(programLog(program)));
    if (!status.ok()) {
        glDeleteProgram(program);
        return status.error();
    }
    return program;
}

using Spirv = std::vector<std::vector<uint32_t>>;

// glslang's verdict on every stage; its diagnostics name kernel files and lines.
Result<Spirv> toSpirv(std::span<const ShaderSource* const> stages) {
    Spirv modules;
    for (const ShaderSource* source : stages) {
        CAVITY_ASSIGN(auto words, kernels::compileToSpirv(*source, Api::OpenGL));
        modules.push_back(std::move(words));
    }
    return modules;
}

// Any failure here is a reason to fall back, reported as one line.
Result<GLuint> fromSpirv(std::span<const ShaderSource* const> stages, const Spirv& modules) {
    Shaders shaders;
    for (size_t i = 0; i < stages.size(); ++i) {
        const ShaderSource& source = *stages[i];
        CAVITY_ASSIGN(const GLuint shader, createShader(source, shaders));
        glShaderBinary(1, &shader, GL_SHADER_BINARY_FORMAT_SPIR_V_ARB, modules[i].data(),
                       GLsizei(modules[i].size() * sizeof(uint32_t)));
        glSpecializeShader(shader, "main", 0, nullptr, nullptr);
        CAVITY_TRY(checkGl("glShaderBinary + glSpecializeShader " + who(source)));
        if (!compiled(shader))
            return internal("gl: glSpecializeShader " + who(source) + ": " + oneLine(shaderLog(shader)));
    }
    return link(shaders, *stages.front());
}

Result<GLuint> fromGlsl(std::span<const ShaderSource* const> stages) {
    Shaders shaders;
    for (const ShaderSource* source : stages) {
        CAVITY_ASSIGN(const GLuint shader, createShader(*source, shaders));
        const char* text = source->glsl.c_str();
        const GLint length = GLint(source->glsl.size());
        glShaderSource(shader, 1, &text, &length);
        glCompileShader(shader);
        CAVITY_TRY(checkGl("glCompileShader " + who(*source)));
        if (!compiled(shader))
            return internal("gl: compile " + source->name + ": " + kernels::nameSourceLines(shaderLog(shader), source->files));
    }
    return link(shaders, *stages.front());
}

}  // namespace

Result<BuiltProgram> buildProgram(std::span<const ShaderSource* const> stages, const std::string& spirvUnusable) {
    if (stages.empty()) return internal("gl: buildProgram: no shader stages");
    std::string reason = spirvUnusable;
    std::optional<Error> rejected;   // glslang's diagnostics, when it rejects the source
    if (reason.empty()) {
        auto modules = toSpirv(stages);
        auto spirv = modules ? fromSpirv(stages, *modules) : Result<GLuint>(modules.error());
        if (spirv) return BuiltProgram{*spirv, {ShaderPath::Spirv, {}, {}, {}}};
        if (!modules) rejected = modules.error();
        reason = oneLine(spirv.error().message);
    }
    auto glsl = fromGlsl(stages);
    if (glsl) return BuiltProgram{*glsl, {ShaderPath::GlslFallback, reason, {}, {}}};
    // Mesa reports most parser errors against source string 0 (its location
    // merge drops the #line source number), so its log can name the wrong
    // kernel file. When glslang rejects the source too, its diagnostics win.
    if (!rejected && !spirvUnusable.empty()) {
        auto modules = toSpirv(stages);
        if (!modules) rejected = modules.error();
    }
    // glslang's rejection is the source's fault, as on Vulkan, with its code
    // (a kernel that does not compile is bad input on either API).
    if (rejected) {
        std::string message = rejected->message;
        while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
        return Error{rejected->code, message};
    }
    return glsl.error();
}

}  // namespace cavity::gpu::gl
