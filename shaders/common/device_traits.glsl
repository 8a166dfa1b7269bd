// What the device compiling the shader is like, as specialization constants the pipeline sets for
// every shader (gpu/pipeline.cpp); a shader that declares none ignores them.
#ifndef OBSCURA_DEVICE_TRAITS_GLSL
#define OBSCURA_DEVICE_TRAITS_GLSL

// A CPU device (lavapipe/llvmpipe): it compiles every inlined copy of a function into each loop
// that holds it, for every lane, so shaders keep one call site of a large function where a GPU's
// compiler is better served by copies specialised for their constant arguments.
layout(constant_id = 0) const bool COMPACT_CODE = false;

#endif
