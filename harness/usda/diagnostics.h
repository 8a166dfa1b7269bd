// Collects warnings for a stage, keeping the first of each kind so a repeated problem is reported once.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "harness/usda/stage.h"

namespace obscura::usda {

class DiagnosticSink {
public:
    void warn(const std::string& kind, const SourceLocation& where, const std::string& message) {
        if (kinds_.insert(kind).second) warnings_.push_back(Warning{where, message});
    }
    std::vector<Warning> take() { return std::move(warnings_); }

private:
    std::set<std::string> kinds_;
    std::vector<Warning> warnings_;
};

// A kind of warning given once for each place it concerns: `kind` at `where`.
inline std::string kindAt(const std::string& kind, const SourceLocation& where) {
    return kind + "@" + where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column);
}

// Thrown while composing and caught by Stage::open: a root layer that cannot be read, a cycle, or a
// composition limit passed.
struct CompositionFailure {
    Error error;
};

}  // namespace obscura::usda
