#version 450 core
// The G-buffer of the splatting (Rohat listing 5.3, §5.1.4): world position with the object's
// id + 1 in w (0: nothing written, the validity flag), and the unit normal facing the viewer.

#include "sss/shaders/subsurface_interface.h"

layout(location = SL_SSS_GBUFFER_OBJECT) uniform float object_id;  // index + 1
in vec3 world_position;
in vec3 world_normal;
layout(location = 0) out vec4 position_id;
layout(location = 1) out vec4 normal_out;
void main() {
    vec3 n = normalize(world_normal);
    position_id = vec4(world_position, object_id);
    normal_out = vec4(gl_FrontFacing ? n : -n, 0.0);
}
