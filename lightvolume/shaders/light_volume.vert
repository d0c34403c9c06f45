#version 450 core
// The light volume's faces (lightvolume/shaders/grid.glsl), made from the shadow map on the GPU:
// no vertex buffer, the index buffer alone (lightvolume::light_volume_triangles). The fragments
// are the region pass's (analytic/shaders/regions.frag): back faces add G(z), front faces
// subtract it.
#include "gl/shaders/frame_uniforms.h"
#include "lightvolume/shaders/grid.glsl"
out vec3 world_position;
void main() {
    world_position = light_volume_vertex(gl_VertexID);
    gl_Position = frame.view_projection * vec4(world_position, 1.0);
}
