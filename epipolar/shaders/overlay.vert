#version 450 core
// The previewer's overlay of the epipolar samples: one point per sample at its window position,
// orange where it was marched, blue where it was interpolated; slices that cross no pixel are
// left out.
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
layout(location = SL_EPIPOLAR_GRID) uniform ivec2 grid;
layout(binding = SL_EPIPOLAR_COORDINATES_UNIT) uniform sampler2D coordinates;
layout(binding = SL_EPIPOLAR_MARKS_UNIT) uniform isampler2D marks;
layout(location = 0) out vec3 colour;

void main() {
    ivec2 id = ivec2(gl_VertexID % grid.x, gl_VertexID / grid.x);
    vec4 c = texelFetch(coordinates, id, 0);
    bool marched = texelFetch(marks, id, 0).x != 0;
    colour = marched ? vec3(1.0, 0.45, 0.05) : vec3(0.15, 0.45, 1.0);
    gl_Position = c.w < 0.0 ? vec4(2.0, 2.0, 2.0, 1.0)
                            : vec4(2.0 * c.xy / frame.display.yz - 1.0, 0.0, 1.0);
}
