#version 450 core
// Coloured lines or triangles under one matrix (beam outlines, the light's view of the leaves).
layout(location = 0) in vec3 position;
layout(location = 1) in vec4 vertex_color;
layout(location = 0) uniform mat4 view_projection;
out vec3 world_position;
out vec4 line_color;
void main() {
    world_position = position;
    line_color = vertex_color;
    gl_Position = view_projection * vec4(position, 1.0);
}
