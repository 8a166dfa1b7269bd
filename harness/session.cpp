#include "harness/session.h"

#include "harness/exit_codes.h"
#include "harness/import/assimp_to_usda.h"

#include <cstdio>
#include <cstdlib>
#include <future>
#include <utility>

namespace obscura::harness {

void PhaseClock::lap(const char* name) {
    auto now = std::chrono::steady_clock::now();
    char text[96];
    std::snprintf(text, sizeof(text), "%s%s %.0f ms", phases_.empty() ? "" : ", ", name,
                  std::chrono::duration<double, std::milli>(now - started_).count());
    phases_ += text;
    started_ = now;
}

std::string PhaseClock::report() { return std::exchange(phases_, {}); }

std::variant<LoadedPlugin, SessionError> loadBestPlugin() {
    const char* env = std::getenv("OBSCURA_PLUGINPATH");
    DiscoveryResult found = discoverPlugins(env ? env : "", defaultPluginDir());
    for (const auto& problem : found.problems) std::fprintf(stderr, "obscura: warning: %s\n", problem.c_str());
    if (found.plugins.empty())
        return SessionError{kExitPluginOrDevice,
                            "no renderer plugin found (searched OBSCURA_PLUGINPATH and the plugin folder beside the "
                            "obscura executable)"};
    std::string reasons;
    for (const auto& info : found.plugins) {
        auto loaded = loadPlugin(info);
        if (auto* plugin = std::get_if<LoadedPlugin>(&loaded)) return std::move(*plugin);
        reasons += "\n  " + std::get<std::string>(loaded);
    }
    return SessionError{kExitPluginOrDevice, "no plugin could be loaded:" + reasons};
}

namespace {

// "file:line:column: " as compilers write it, "file: " without a line, or "" for no location.
std::string locationPrefix(const usda::SourceLocation& where) {
    if (where.file.empty()) return {};
    if (where.line <= 0) return where.file + ": ";
    return where.file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) + ": ";
}

}  // namespace

void printHostMessage(const HostMessage& m) {
    std::fprintf(stderr, "obscura: %s%s: %s\n", locationPrefix(m.where).c_str(), m.error ? "error" : "warning",
                 m.text.c_str());
}

// A message about a prim names where its offending attribute was authored (delegate_message.h).
void Session::logToStderr(void* user, ObscuraLogLevel level, const char* message) {
    auto* self = static_cast<Session*>(user);
    if (level == OBSCURA_LOG_ERROR) ++self->loggedErrors_;
    if (level < (self->verbose_ ? OBSCURA_LOG_INFO : OBSCURA_LOG_WARNING)) return;
    std::string where;
    if (self->host_)
        if (auto about = parsePrimMessage(message))
            if (auto location = self->host_->locate(*about)) where = locationPrefix(*location);
    std::fprintf(stderr, "obscura: %s%s: %s\n", where.c_str(),
                 level == OBSCURA_LOG_ERROR ? "error" : level == OBSCURA_LOG_WARNING ? "warning" : "info", message);
}

ObscuraRenderStats Session::renderStats(ObscuraInteropStats* interop) const {
    ObscuraRenderStats stats{};
    stats.sType = OBSCURA_STRUCTURE_TYPE_RENDER_STATS;
    stats.structSize = sizeof(stats);
    if (interop) {
        *interop = {OBSCURA_STRUCTURE_TYPE_INTEROP_STATS, nullptr, sizeof(ObscuraInteropStats), 0};
        stats.pNext = interop;
    }
    api().getRenderStats(delegate_, &stats);
    return stats;
}

std::vector<ObscuraPassTiming> Session::passTimings() const {
    uint32_t count = 0;
    api().getPassTimings(delegate_, nullptr, &count);
    std::vector<ObscuraPassTiming> timings(count);
    for (auto& t : timings) t.structSize = sizeof(ObscuraPassTiming);
    api().getPassTimings(delegate_, timings.data(), &count);
    timings.resize(count);
    return timings;
}

std::string Session::deviceName() const { return renderStats().deviceName; }

std::vector<std::string> withMsaaSetting(std::vector<std::string> settings, const std::optional<int>& msaa) {
    if (msaa) settings.push_back("msaa=" + std::to_string(*msaa));
    return settings;
}

std::variant<std::unique_ptr<usda::Stage>, SessionError> Session::openStage(const std::string& scenePath,
                                                                            const usda::StageOptions& options) {
    // glTF, FBX and OBJ arrive through Assimp as a USD layer: one scene model for every format.
    std::variant<std::unique_ptr<usda::Stage>, usda::Error> opened = usda::Error{};
    if (isAssimpFormat(scenePath)) {
        auto imported = importWithAssimp(scenePath);
        if (auto* error = std::get_if<ImportError>(&imported)) return SessionError{kExitBadInput, error->message};
        for (const auto& w : std::get<ImportResult>(imported).warnings)
            std::fprintf(stderr, "obscura: warning: %s: %s\n", scenePath.c_str(), w.c_str());
        opened = usda::Stage::openFromString(std::get<ImportResult>(imported).usda, scenePath, options);
    } else {
        opened = usda::Stage::open(scenePath, options);
    }
    if (auto* error = std::get_if<usda::Error>(&opened)) return SessionError{kExitBadInput, error->str()};
    auto stage = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));
    for (const auto& w : stage->warnings())
        std::fprintf(stderr, "obscura: warning: %s:%d:%d: %s\n", w.where.file.c_str(), w.where.line, w.where.column,
                     w.message.c_str());
    return stage;
}

void Session::replaceScene(std::unique_ptr<usda::Stage> stage, std::unique_ptr<UsdSceneHost> host) {
    host_ = std::move(host);
    stage_ = std::move(stage);
}

std::variant<std::unique_ptr<Session>, SessionError> Session::open(const std::string& scenePath,
                                                                  const usda::StageOptions& options) {
    std::unique_ptr<Session> s(new Session());
    // The plugin is loaded and its delegate made (the GPU device: 40 ms on lavapipe, 200 ms on an
    // H100) while the stage is read, which a production scene takes as long for; a scene that
    // cannot be read is reported first.
    std::future<std::optional<SessionError>> delegate = std::async(std::launch::async, [session = s.get()] {
        return session->createDelegate();
    });
    auto opened = openStage(scenePath, options);
    s->phases_.lap("stage");
    std::optional<SessionError> delegateError = delegate.get();
    s->phases_.lap("delegate");
    if (auto* error = std::get_if<SessionError>(&opened)) return *error;
    if (delegateError) return *delegateError;
    s->stage_ = std::move(std::get<std::unique_ptr<usda::Stage>>(opened));

    // The scene's units, for settings given in metres (ssao:radius).
    double metersPerUnit = s->stage_->metadata().metersPerUnit;
    ObscuraValue units{OBSCURA_VALUE_DOUBLE, 0, 1, &metersPerUnit};
    s->api().setRenderSetting(s->delegate_, "metersPerUnit", &units);
    double timeCodesPerSecond = s->stage_->metadata().timeCodesPerSecond;
    ObscuraValue rate{OBSCURA_VALUE_DOUBLE, 0, 1, &timeCodesPerSecond};
    s->api().setRenderSetting(s->delegate_, "timeCodesPerSecond", &rate);

    s->host_ = std::make_unique<UsdSceneHost>(*s->stage_);
    s->host_->setMessageSink(printHostMessage);
    if (s->api().setSceneDelegate(s->delegate_, &s->host_->sceneDelegate()) != OBSCURA_OK ||
        s->host_->populate(s->api(), s->delegate_) != OBSCURA_OK)
        return SessionError{kExitPluginOrDevice, s->lastError()};
    s->phases_.lap("populate");
    return s;
}

std::optional<SessionError> Session::createDelegate() {
    auto plugin = loadBestPlugin();
    if (auto* error = std::get_if<SessionError>(&plugin)) return *error;
    plugin_.emplace(std::move(std::get<LoadedPlugin>(plugin)));
    ObscuraDelegateCreateInfo info{OBSCURA_STRUCTURE_TYPE_DELEGATE_CREATE_INFO, nullptr, sizeof(ObscuraDelegateCreateInfo),
                                   nullptr, -1, &Session::logToStderr, this};
    if (api().createDelegate(&info, &delegate_) != OBSCURA_OK)
        return SessionError{kExitPluginOrDevice, std::string("cannot create a delegate: ") + api().lastError(nullptr)};
    return std::nullopt;
}

Session::~Session() {
    if (delegate_) api().destroyDelegate(delegate_);
}

std::optional<SessionError> Session::applySettings(const std::vector<std::string>& settings) {
    for (const auto& kv : settings) {
        auto eq = kv.find('=');
        if (eq == std::string::npos || eq == 0)
            return SessionError{kExitUsage, "--set expects key=value, got '" + kv + "'"};
        std::string key = kv.substr(0, eq), text = kv.substr(eq + 1);
        ObscuraValue value{};
        double number = 0;
        int32_t flag = 0;
        std::string token;
        const char* tokenPtr = nullptr;
        char* end = nullptr;
        if (text == "true" || text == "on" || text == "false" || text == "off") {
            flag = (text == "true" || text == "on") ? 1 : 0;
            value = {OBSCURA_VALUE_BOOL, 0, 1, &flag};
        } else if (number = std::strtod(text.c_str(), &end); end && *end == '\0' && !text.empty()) {
            value = {OBSCURA_VALUE_DOUBLE, 0, 1, &number};
        } else {
            token = text;
            tokenPtr = token.c_str();
            value = {OBSCURA_VALUE_TOKEN, 0, 1, &tokenPtr};
        }
        if (api().setRenderSetting(delegate_, key.c_str(), &value) != OBSCURA_OK)
            return SessionError{kExitUsage, "--set " + kv + ": " + lastError()};
    }
    return std::nullopt;
}

}  // namespace obscura::harness
