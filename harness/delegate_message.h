// What a delegate's log message is about, so that the host can name where it was authored.
// The delegate reports bad prim data as "skipped prim <path>: <reason>" (an error) or
// "<path>: <reason>" (a warning); every reason starts with the attribute it concerns, written as
// USD names it, followed by the value's index where there is one ("faceVertexIndices[7] = 9 is
// outside the 4 points", "points: element 1 is NaN", "positions has 1 entries for 2 instances"),
// or says which attribute the host failed to provide ("the host failed to provide primvars:st").
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace obscura::harness {

struct PrimMessage {
    std::string primPath;   // "/World/Mesh"
    std::string attribute;  // "faceVertexIndices"; "" when the reason names none
};

// nullopt when the message is not about a prim.
std::optional<PrimMessage> parsePrimMessage(std::string_view message);

}  // namespace obscura::harness
