// importWithAssimp: importInThisProcess in a child process (harness/import/child_server.h), one
// for the process's imports until one crashes it. The child sends a mark at each ImportStep, then
// the result; when it dies, the last mark says whose code it died in.
#include <optional>

#include "harness/import/assimp_to_usda.h"
#include "harness/import/child_server.h"
#include "harness/usda/temporary_files.h"

namespace obscura::harness {

namespace {

// The child's frames: a step mark, then kResult followed by the USD text, the warnings' count, the
// warnings, the count of temporary files and each one's key and path; or kError and the message.
const std::string kReaderStarts = "S", kReaderReturned = "R", kResult = "O", kError = "E";

void sendAnswer(const std::variant<ImportResult, ImportError>& imported, ReplyChannel& parent) {
    if (const auto* error = std::get_if<ImportError>(&imported)) {
        parent.send(kError);
        parent.send(error->message);
        return;
    }
    const ImportResult& result = std::get<ImportResult>(imported);
    parent.send(kResult);
    parent.send(result.usda);
    parent.send(std::to_string(result.warnings.size()));
    for (const std::string& warning : result.warnings) parent.send(warning);
    // The embedded images the conversion wrote, for the parent to adopt.
    const std::map<std::string, std::string> files = usda::temporaryFilesByKey();
    parent.send(std::to_string(files.size()));
    for (const auto& [key, path] : files) {
        parent.send(key);
        parent.send(path);
    }
}

// What the child sent: its last step mark, and its answer if the frames hold a whole one.
struct Received {
    std::string lastStep;
    std::optional<std::variant<ImportResult, ImportError>> answer;
    std::map<std::string, std::string> temporaryFiles;
};

class Frames {
public:
    explicit Frames(const std::vector<std::string>& frames) : frames_(frames) {}

    bool done() const { return at_ == frames_.size(); }
    std::optional<std::string> next() {
        if (done()) return std::nullopt;
        return frames_[at_++];
    }
    std::optional<unsigned long> count() {
        const std::optional<std::string> digits = next();
        if (!digits || digits->empty() || digits->find_first_not_of("0123456789") != std::string::npos)
            return std::nullopt;
        return std::stoul(*digits);
    }

private:
    const std::vector<std::string>& frames_;
    size_t at_ = 0;
};

// Fills received's answer and files when the frames hold them whole.
void receiveAnswer(const std::string& tag, Frames& in, Received& received) {
    if (tag == kError) {
        std::optional<std::string> message = in.next();
        if (message && in.done()) received.answer = ImportError{*message};
        return;
    }
    ImportResult result;
    std::optional<std::string> usda = in.next();
    std::optional<unsigned long> warnings = in.count();
    if (!usda || !warnings) return;
    result.usda = std::move(*usda);
    for (unsigned long n = *warnings; n > 0; --n) {
        std::optional<std::string> warning = in.next();
        if (!warning) return;
        result.warnings.push_back(std::move(*warning));
    }
    std::optional<unsigned long> files = in.count();
    if (!files) return;
    for (unsigned long n = *files; n > 0; --n) {
        std::optional<std::string> key = in.next(), path = in.next();
        if (!key || !path) return;
        received.temporaryFiles[*key] = *path;
    }
    if (in.done()) received.answer = std::move(result);
}

Received receive(const std::vector<std::string>& frames) {
    Received received;
    Frames in(frames);
    while (std::optional<std::string> tag = in.next()) {
        if (*tag == kReaderStarts || *tag == kReaderReturned) {
            received.lastStep = *tag;
        } else {
            if (*tag == kResult || *tag == kError) receiveAnswer(*tag, in, received);
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
            parent.send(step == ImportStep::ReaderStarts ? kReaderStarts : kReaderReturned);
        });
        sendAnswer(imported, parent);
    });
    std::error_code ec;
    const ChildReply child = importer.call(std::filesystem::current_path(ec).string() + '\0' + file.string());
    const std::string failed = "cannot import " + file.string() + ": ";
    if (child.end == ChildReply::End::NoChild) return ImportError{failed + child.how};
    Received received = receive(child.frames);
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
