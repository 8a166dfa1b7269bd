// importWithAssimp: importInThisProcess in a child process (harness/import/child_server.h), one
// for the process's imports until one crashes it. The child sends a mark at each ImportStep, then
// the result; when it dies, the last mark says whose code it died in.
#include <cstdint>
#include <cstring>
#include <optional>

#include "harness/import/assimp_to_usda.h"
#include "harness/import/child_server.h"
#include "harness/usda/temporary_files.h"

namespace obscura::harness {

namespace {

// The child's messages: a step mark (one byte), or a result or an error, each followed by
// length-prefixed strings (the USD text, the warnings' count and the warnings, then the count of
// temporary files and each one's key and path; or the error's message).
constexpr char kReaderStarts = 'S', kReaderReturned = 'R', kResult = 'O', kError = 'E';

std::string lengthPrefixed(const std::string& text) {
    const uint64_t size = text.size();
    std::string bytes(sizeof size, '\0');
    std::memcpy(bytes.data(), &size, sizeof size);
    return bytes + text;
}

std::string encode(const std::variant<ImportResult, ImportError>& imported) {
    if (const auto* error = std::get_if<ImportError>(&imported))
        return std::string(1, kError) + lengthPrefixed(error->message);
    const ImportResult& result = std::get<ImportResult>(imported);
    std::string bytes = std::string(1, kResult) + lengthPrefixed(result.usda);
    bytes += lengthPrefixed(std::to_string(result.warnings.size()));
    for (const std::string& warning : result.warnings) bytes += lengthPrefixed(warning);
    // The embedded images the conversion wrote, for the parent to adopt.
    const std::map<std::string, std::string> files = usda::temporaryFilesByKey();
    bytes += lengthPrefixed(std::to_string(files.size()));
    for (const auto& [key, path] : files) bytes += lengthPrefixed(key) + lengthPrefixed(path);
    return bytes;
}

// What the child sent: its last step mark, and its answer if the bytes hold a whole one.
struct Received {
    char lastStep = 0;
    std::optional<std::variant<ImportResult, ImportError>> answer;
    std::map<std::string, std::string> temporaryFiles;
};

class Decoder {
public:
    explicit Decoder(const std::string& bytes) : bytes_(bytes) {}

    bool done() const { return at_ == bytes_.size(); }
    char tag() { return bytes_[at_++]; }

    std::optional<std::string> text() {
        uint64_t size = 0;
        if (bytes_.size() - at_ < sizeof size) return std::nullopt;
        std::memcpy(&size, bytes_.data() + at_, sizeof size);
        at_ += sizeof size;
        if (bytes_.size() - at_ < size) return std::nullopt;
        std::string out = bytes_.substr(at_, size);
        at_ += size;
        return out;
    }

    std::optional<unsigned long> count() {
        const std::optional<std::string> digits = text();
        if (!digits || digits->empty() || digits->find_first_not_of("0123456789") != std::string::npos)
            return std::nullopt;
        return std::stoul(*digits);
    }

private:
    const std::string& bytes_;
    size_t at_ = 0;
};

// Fills received's answer and files when the bytes hold them whole.
void decodeAnswer(char tag, Decoder& in, Received& received) {
    if (tag == kError) {
        std::optional<std::string> message = in.text();
        if (message && in.done()) received.answer = ImportError{*message};
        return;
    }
    ImportResult result;
    std::optional<std::string> usda = in.text();
    std::optional<unsigned long> warnings = in.count();
    if (!usda || !warnings) return;
    result.usda = std::move(*usda);
    for (unsigned long n = *warnings; n > 0; --n) {
        std::optional<std::string> warning = in.text();
        if (!warning) return;
        result.warnings.push_back(std::move(*warning));
    }
    std::optional<unsigned long> files = in.count();
    if (!files) return;
    for (unsigned long n = *files; n > 0; --n) {
        std::optional<std::string> key = in.text(), path = in.text();
        if (!key || !path) return;
        received.temporaryFiles[*key] = *path;
    }
    if (in.done()) received.answer = std::move(result);
}

Received decode(const std::string& bytes) {
    Received received;
    Decoder in(bytes);
    while (!in.done()) {
        const char tag = in.tag();
        if (tag == kReaderStarts || tag == kReaderReturned) {
            received.lastStep = tag;
        } else {
            if (tag == kResult || tag == kError) decodeAnswer(tag, in, received);
            break;
        }
    }
    return received;
}

}  // namespace

std::variant<ImportResult, ImportError> importWithAssimp(const std::filesystem::path& file) {
    // The request: this process's working folder, a NUL, and the file as given, so that a relative
    // path means what it means here and messages name the file as the user did.
    static ChildServer importer([](const std::string& request, ReplyChannel& parent) {
        const size_t split = request.find('\0');
        std::error_code ec;
        std::filesystem::current_path(request.substr(0, split), ec);
        auto imported = importInThisProcess(request.substr(split + 1), [&](ImportStep step) {
            parent.send(std::string(1, step == ImportStep::ReaderStarts ? kReaderStarts : kReaderReturned));
        });
        parent.send(encode(imported));
    });
    std::error_code ec;
    const ChildReply child = importer.call(std::filesystem::current_path(ec).string() + '\0' + file.string());
    const std::string failed = "cannot import " + file.string() + ": ";
    if (child.end == ChildReply::End::NoChild) return ImportError{failed + child.how};
    Received received = decode(child.bytes);
    const bool answered = child.end == ChildReply::End::Answered;
    if (answered && received.answer) {
        usda::adoptTemporaryFiles(received.temporaryFiles);
        return std::move(*received.answer);
    }
    const std::string how = answered ? "its answer was cut short" : child.how;
    if (received.lastStep == kReaderStarts)
        return ImportError{failed + "Assimp's reader crashed on it (" + how +
                               "); the file is malformed or uses what this Assimp cannot read",
                           ImportError::Crash::InReader};
    return ImportError{failed + "the import crashed outside Assimp's reader (" + how + ")",
                       ImportError::Crash::InConversion};
}

}  // namespace obscura::harness
