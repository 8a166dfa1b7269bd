// Depth conversions shared by the passes that read the G-buffer's depth.
#ifndef OBSCURA_VIEW_DEPTH_GLSL
#define OBSCURA_VIEW_DEPTH_GLSL

// Distance along the view axis (the camera looks down -z) of a device depth. Solves
// depth = (A z + B) / (C z + D) for the view-space z, which covers the perspective and the
// orthographic projections of delegate/prims/camera.cpp alike (and their sub-pixel jitter, which
// moves only x and y).
float linearDepthFromDevice(mat4 projection, float depth) {
    float a = projection[2][2], b = projection[3][2], c = projection[2][3], d = projection[3][3];
    return (b - depth * d) / (a - depth * c);
}

#endif
