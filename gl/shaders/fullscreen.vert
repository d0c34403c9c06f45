#version 450 core
// One triangle covering the viewport; uv in [0, 1] over the visible part.
out vec2 uv;
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    uv = p;
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
