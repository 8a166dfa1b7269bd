// Errors as values: expected failures (no device, unsupported format, out of memory) travel as
// Result<T>; programmer errors are asserts.
#pragma once

#include <string>
#include <utility>
#include <variant>

namespace obscura {

struct Failure {
    std::string message;
};

template <typename T>
class Result {
public:
    Result(T value) : v_(std::move(value)) {}
    Result(Failure f) : v_(std::move(f)) {}
    bool ok() const { return v_.index() == 0; }
    explicit operator bool() const { return ok(); }
    T& value() { return std::get<0>(v_); }
    const T& value() const { return std::get<0>(v_); }
    T& operator*() { return value(); }
    T* operator->() { return &value(); }
    const std::string& error() const { return std::get<1>(v_).message; }

private:
    std::variant<T, Failure> v_;
};

}  // namespace obscura
