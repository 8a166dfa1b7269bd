#version 460
// One triangle that covers the whole viewport, from the vertex index alone (no vertex buffer):
// (-1, -1), (3, -1), (-1, 3) in clip space. Full-screen raster passes draw it with 3 vertices.
void main() {
    vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
