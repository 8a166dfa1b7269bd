// What the alpha channel of the frame's HDR colour holds, for the pass that reads it last (the AOV
// readback, which also tone maps). The light accumulation has none (B10G11R11, or RGBA16F left at
// 1): coverage is then the G-buffer's, one sample per pixel. Temporal AA accumulates coverage like
// the colour, so at anti-aliased silhouettes alpha matches the premultiplied colour.
#pragma once

namespace obscura::passes {

enum class HdrAlpha { None, Coverage };

}  // namespace obscura::passes
