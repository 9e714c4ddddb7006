#include "gl/gl_timestamps.h"

#include "gl/gl_errors.h"

namespace cavity::gpu::gl {

void Timestamps::release() {
    if (!pool_.empty()) glDeleteQueries(GLsizei(pool_.size()), pool_.data());
    pool_.clear();
    reset();
}

void Timestamps::reset() {
    used_ = 0;
    scopes_.clear();
    stack_.clear();
}

Result<GLuint> Timestamps::stamp(const std::string& what) {
    if (used_ == pool_.size()) {
        GLuint query = 0;
        glCreateQueries(GL_TIMESTAMP, 1, &query);
        CAVITY_TRY(checkGl("glCreateQueries(GL_TIMESTAMP) for " + what));
        pool_.push_back(query);
    }
    const GLuint query = pool_[used_++];
    glQueryCounter(query, GL_TIMESTAMP);
    CAVITY_TRY(checkGl("glQueryCounter(GL_TIMESTAMP) for " + what));
    return query;
}

Status Timestamps::begin(const std::string& name) {
    CAVITY_ASSIGN(const GLuint query, stamp("beginScope '" + name + "'"));
    stack_.push_back(scopes_.size());
    scopes_.push_back({name, query, 0});
    return {};
}

Status Timestamps::end() {
    if (stack_.empty()) return internal("gl: endScope without an open scope");
    Scope& scope = scopes_[stack_.back()];
    stack_.pop_back();
    CAVITY_ASSIGN(scope.end, stamp("endScope '" + scope.name + "'"));
    return {};
}

const std::string* Timestamps::open() const { return stack_.empty() ? nullptr : &scopes_[stack_.back()].name; }

Result<std::vector<ScopeTime>> Timestamps::resolve() const {
    std::vector<ScopeTime> times;
    times.reserve(scopes_.size());
    for (const Scope& scope : scopes_) {
        GLuint64 begin = 0, end = 0;
        glGetQueryObjectui64v(scope.begin, GL_QUERY_RESULT, &begin);
        glGetQueryObjectui64v(scope.end, GL_QUERY_RESULT, &end);
        CAVITY_TRY(checkGl("glGetQueryObjectui64v(GL_QUERY_RESULT) for scope '" + scope.name + "'"));
        // Signed: a driver whose counter runs backwards shows up, not wraps.
        times.push_back({scope.name, (double(end) - double(begin)) / 1e6});
    }
    return times;
}

}  // namespace cavity::gpu::gl
