#include "harness/delegate_message.h"

namespace obscura::harness {
namespace {

bool isNameChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == ':';
}

// The USD attribute name a reason starts with: an identifier with namespaces ("primvars:st"),
// without a trailing ':' ("points: element 1 is NaN").
std::string leadingName(std::string_view text, bool anyFollower) {
    size_t end = 0;
    while (end < text.size() && isNameChar(text[end])) ++end;
    std::string_view name = text.substr(0, end);
    while (!name.empty() && name.back() == ':') name.remove_suffix(1);
    if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return {};
    // A reason in words ("the instances change ...") names no attribute: attribute names are
    // followed by '[', ':', or " has"/" is"/" sum".
    const std::string_view after = text.substr(name.size());
    const bool named = anyFollower || after.empty() || after[0] == '[' || after[0] == ':' || after.starts_with(" has ") ||
                       after.starts_with(" is ") || after.starts_with(" sum ");
    return named ? std::string(name) : std::string();
}

}  // namespace

std::optional<PrimMessage> parsePrimMessage(std::string_view message) {
    constexpr std::string_view kSkipped = "skipped prim ";
    if (message.starts_with(kSkipped)) message.remove_prefix(kSkipped.size());
    if (!message.starts_with('/')) return std::nullopt;
    const size_t colon = message.find(": ");
    if (colon == std::string_view::npos) return std::nullopt;
    PrimMessage out{std::string(message.substr(0, colon)), {}};
    std::string_view reason = message.substr(colon + 2);
    constexpr std::string_view kNotProvided = "the host failed to provide ";
    const bool notProvided = reason.starts_with(kNotProvided);
    if (notProvided) reason.remove_prefix(kNotProvided.size());
    out.attribute = leadingName(reason, notProvided);
    return out;
}

}  // namespace obscura::harness
