// Errors are values until the edge: every fallible call returns a Status or a
// Result<T> carrying what was attempted and with what. Only main() turns an
// ErrorCode into a process exit code (see README, "Exit codes").
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>

namespace cavity {

// The codes any layer may return; each is also the process exit code that
// main() gives it (README, "Exit codes"), so none names one layer's outcome.
enum class ErrorCode {
    CheckFailed = 1,          // a result failed a check (an image against its reference, a non-finite
                              // pixel): the program worked, the thing it measured did not pass
    BadInput = 2,             // a flag, file or value the user gave is wrong
    BackendUnavailable = 3,   // no ICD, no EGL device, ...
    Internal = 4,             // a GPU call failed after the backend started
    Unreachable = 5,          // a server we were pointed at (an image store, a results database)
                              // cannot be reached, refused us, or lacks an object
    Corrupt = 6,              // stored data fails its own check (an object's pixels against its digest)
};

struct Error {
    ErrorCode code = ErrorCode::Internal;
    std::string message;
};

inline Error badInput(std::string m) { return {ErrorCode::BadInput, std::move(m)}; }
inline Error unavailable(std::string m) { return {ErrorCode::BackendUnavailable, std::move(m)}; }
inline Error internal(std::string m) { return {ErrorCode::Internal, std::move(m)}; }
inline Error unreachable(std::string m) { return {ErrorCode::Unreachable, std::move(m)}; }
inline Error corrupt(std::string m) { return {ErrorCode::Corrupt, std::move(m)}; }

// A value or an error, in the spirit of std::expected (C++23).
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : v_(std::move(value)) {}
    Result(Error error) : v_(std::move(error)) {}

    bool ok() const { return v_.index() == 0; }
    explicit operator bool() const { return ok(); }
    T& value() & { return std::get<0>(v_); }
    const T& value() const& { return std::get<0>(v_); }
    T&& value() && { return std::get<0>(std::move(v_)); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    const Error& error() const { return std::get<1>(v_); }

private:
    std::variant<T, Error> v_;
};

class [[nodiscard]] Status {
public:
    Status() = default;
    Status(Error e) : e_(std::move(e)) {}
    static Status success() { return {}; }
    bool ok() const { return !e_; }
    explicit operator bool() const { return ok(); }
    const Error& error() const { return *e_; }

private:
    std::optional<Error> e_;
};

// Propagate an error out of the enclosing function.
#define CAVITY_TRY(expr)                                     \
    do {                                                     \
        auto cavity_try_s_ = (expr);                         \
        if (!cavity_try_s_.ok()) return cavity_try_s_.error(); \
    } while (0)

// Bind the value of a Result or propagate its error.
#define CAVITY_CONCAT_(a, b) a##b
#define CAVITY_CONCAT(a, b) CAVITY_CONCAT_(a, b)
#define CAVITY_ASSIGN(lhs, expr) CAVITY_ASSIGN_(CAVITY_CONCAT(cavity_r_, __LINE__), lhs, expr)
#define CAVITY_ASSIGN_(tmp, lhs, expr)         \
    auto tmp = (expr);                         \
    if (!tmp.ok()) return tmp.error();         \
    lhs = std::move(tmp).value()

}  // namespace cavity
