// What the viewer and the bench share to show a render buffer on a Vulkan device of their own:
// the plugin's exported memory imported (shared, ABI 1.2), or the buffer's mapping copied into
// host-visible memory of that device (readback).
#pragma once

#include "harness/session.h"
#include "harness/view/display_device.h"

#include <memory>
#include <string>
#include <variant>

namespace obscura::harness::view {

// The render buffer at `buffer` exported by the plugin (its descriptors are the caller's:
// DisplaySource::import takes them over), or why it cannot be. From then on every render writes
// the exported memory and the buffer can no longer be mapped.
std::variant<ObscuraExternalBuffer, std::string> exportRenderBuffer(const Session& session, const std::string& buffer);

// readback: the render buffer's mapping copied into `source`, which is made anew where there is
// none or its size or format changed. Returns the problem, or "".
std::string copyRenderBuffer(const Session& session, DisplayDevice& device, const std::string& buffer,
                             std::unique_ptr<DisplaySource>& source);

// `source` into `image` as `view` shows it; a shared source is read once the plugin's last render
// is done (its timeline semaphore at the value of the render stats).
void showSource(const Session& session, DisplayDevice& device, const DisplaySource& source, AovImage& image,
                AovView view);

}  // namespace obscura::harness::view
