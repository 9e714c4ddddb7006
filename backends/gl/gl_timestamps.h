// Named timestamp scopes of one frame: a GL_TIMESTAMP query at each begin and
// end (glQueryCounter), from a pool of query objects reused across frames.
// What the driver returns is reported as is: on llvmpipe the counters do not
// bracket the work (the harness detects that against wall time).
#pragma once

#include "backend.h"

#include <epoxy/gl.h>

#include <string>
#include <vector>

namespace cavity::gpu::gl {

class Timestamps {
public:
    void reset();     // start of a frame
    void release();   // needs the context current; otherwise the queries die with it
    Status begin(const std::string& name);
    Status end();
    // The name of the innermost scope still open, or nullptr.
    const std::string* open() const;
    // After the frame's commands completed: every scope in begin order.
    Result<std::vector<ScopeTime>> resolve() const;

private:
    Result<GLuint> stamp(const std::string& what);

    struct Scope {
        std::string name;
        GLuint begin = 0, end = 0;
    };
    std::vector<GLuint> pool_;
    size_t used_ = 0;
    std::vector<Scope> scopes_;
    std::vector<size_t> stack_;   // indices of open scopes
};

}  // namespace cavity::gpu::gl
