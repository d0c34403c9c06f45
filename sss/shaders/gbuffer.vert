#version 450 core
// Positions and normals of the objects seen from a camera or a light (Rohat listing 5.2), in
// world space.
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 model;
layout(location = 1) uniform mat4 normal_matrix;  // inverse transpose of model
layout(location = 5) uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
void main() {
    vec4 p = model * vec4(position, 1.0);
    world_position = p.xyz;
    world_normal = mat3(normal_matrix) * normal;
    gl_Position = view_projection * p;
}
