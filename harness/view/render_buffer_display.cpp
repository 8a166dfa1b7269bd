#include "harness/view/render_buffer_display.h"

namespace obscura::harness::view {

std::variant<ObscuraExternalBuffer, std::string> exportRenderBuffer(const Session& session, const std::string& buffer) {
    const ObscuraApiV1_2* interop = session.interopApi();
    if (!interop) return "the plugin has no ABI 1.2 (display interop)";
    ObscuraExternalBuffer exported{};
    exported.sType = OBSCURA_STRUCTURE_TYPE_EXTERNAL_BUFFER;
    exported.structSize = sizeof(exported);
    if (interop->exportRenderBuffer(session.delegate(), buffer.c_str(), &exported) != OBSCURA_OK)
        return session.lastError();
    return exported;
}

std::string copyRenderBuffer(const Session& session, DisplayDevice& device, const std::string& buffer,
                             std::unique_ptr<DisplaySource>& source) {
    ObscuraMappedBuffer mapped{OBSCURA_STRUCTURE_TYPE_MAPPED_BUFFER, nullptr, sizeof(mapped)};
    if (session.api().mapRenderBuffer(session.delegate(), buffer.c_str(), &mapped) != OBSCURA_OK)
        return session.lastError();
    if (!source || source->width() != mapped.width || source->height() != mapped.height ||
        source->format() != mapped.format)
        source = DisplaySource::upload(device, mapped.width, mapped.height, mapped.format,
                                       mapped.rowStride * mapped.height);
    source->copyFrom(mapped);
    session.api().unmapRenderBuffer(session.delegate(), buffer.c_str());
    return {};
}

void showSource(const Session& session, DisplayDevice& device, const DisplaySource& source, AovImage& image,
                AovView view) {
    ObscuraInteropStats interop{};
    if (source.shared()) session.renderStats(&interop);
    device.submitAndWait([&](VkCommandBuffer cmd) { image.record(cmd, source, view); }, source.semaphore(),
                         interop.semaphoreValue);
}

}  // namespace obscura::harness::view
