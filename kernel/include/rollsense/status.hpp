// Typed status and error values shared by the kernel, the HAL and every plugin.
//
// Why not bools or bare exceptions: a failure has to travel across a plugin boundary, into Lua and onto a user's
// terminal with enough context to act on ("which servo, what went wrong, what to do"). An Error carries a machine-
// readable code plus a human message; Result<T> carries a value or an Error.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>

namespace rollsense {

enum class ErrorCode {
    ok = 0,
    invalid_argument,  // a value the caller passed is malformed or out of range
    not_found,         // a file, device, plugin, joint or key does not exist
    io_error,          // the OS reported an I/O failure
    timeout,           // a device or operation did not answer in time
    protocol_error,    // a peer answered with something that is not the protocol
    hardware_fault,    // a device reported a fault of its own, or was lost (overload, NACK, unplugged)
    limit_violation,   // a command outside joint / current / velocity limits
    state_error,       // an operation not allowed in the current lifecycle state
    plugin_error,      // a plugin threw or violated its contract
    cancelled,         // the run was cancelled (Ctrl-C, e-stop, budget)
    parse_error,       // a file or script could not be parsed
    unsupported,       // the operation is not implemented by this component
    script_error,      // a roll script raised an error
    bad_setting,       // a --set, --seed or --profile the script or a resumed dataset refuses: exit 2
    bad_profile,       // a profile whose content (a value, a key, a device's params) is refused: exit 3
};

std::string_view to_string(ErrorCode code) noexcept;

struct Error {
    ErrorCode code = ErrorCode::ok;
    std::string message;

    // "<code>: <message>", the form written to logs.
    std::string describe() const;
};

// The outcome of an operation that returns no value.
class [[nodiscard]] Status {
public:
    Status() = default;  // success
    Status(Error error) : error_(std::move(error)) {}
    Status(ErrorCode code, std::string message) : error_{code, std::move(message)} {}

    static Status success() { return {}; }

    bool ok() const noexcept { return error_.code == ErrorCode::ok; }
    explicit operator bool() const noexcept { return ok(); }
    ErrorCode code() const noexcept { return error_.code; }
    const std::string& message() const noexcept { return error_.message; }
    const Error& error() const noexcept { return error_; }

    // Prefix the message with context, e.g. with("plugin 'sim'"). No-op on success.
    Status with_context(std::string_view context) &&;

private:
    Error error_;
};

// Exception form of an Error, for code paths (Lua bindings, CLI) where unwinding is the natural way out.
class StatusError : public std::exception {
public:
    explicit StatusError(Status status) : status_(std::move(status)), what_(status_.error().describe()) {}
    const Status& status() const noexcept { return status_; }
    const char* what() const noexcept override { return what_.c_str(); }

private:
    Status status_;
    std::string what_;
};

// A value or an error.
template <class T>
class [[nodiscard]] Result {
public:
    Result(T value) : state_(std::move(value)) {}
    Result(Error error) : state_(std::move(error)) {}
    Result(Status status) : state_(status.error()) {}
    Result(ErrorCode code, std::string message) : state_(Error{code, std::move(message)}) {}

    bool ok() const noexcept { return state_.index() == 0; }
    explicit operator bool() const noexcept { return ok(); }

    // A failed Result's value is the caller's bug: a logic_error saying the error (was std::get's "wrong index").
    T& value() & { return ok() ? std::get<0>(state_) : throw unchecked(); }
    const T& value() const& { return ok() ? std::get<0>(state_) : throw unchecked(); }
    T&& value() && { return ok() ? std::get<0>(std::move(state_)) : throw unchecked(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    const Error& error() const { return std::get<1>(state_); }
    Status status() const { return ok() ? Status{} : Status{error()}; }

private:
    std::logic_error unchecked() const { return std::logic_error("the value of a failed Result, " + error().describe()); }
    std::variant<T, Error> state_;
};

// Throw if a status is an error; return the value of a Result otherwise.
inline void throw_if_error(const Status& s) { if (!s.ok()) throw StatusError(s); }
template <class T>
T value_or_throw(Result<T> r) { return r ? std::move(r).value() : throw StatusError(r.status()); }

}  // namespace rollsense
