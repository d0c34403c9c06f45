#pragma once
// Moschos algorithm 4 (§3.2.5, figure 3.18): the eye ray's trace [0, trace_end] clipped to the
// light's influence volume, a convex polyhedron given by its outward planes, with the six cases
// of the thesis:
//   A  the ray misses the volume: nothing to sample;
//   B  it starts inside and leaves before trace_end: end at the exit;
//   C  it starts inside and is still inside at trace_end: no clipping;
//   D  it enters and leaves before trace_end: start at the entry, end at the exit;
//   E  it enters before trace_end and leaves after it: start at the entry (the figure's caption;
//      the pseudo code's "trace_end <- last intersection" would march past the surface);
//   F  it enters after trace_end: nothing to sample.
// sampling/shaders/ray_clip.glsl is the GLSL twin (tested against this).

#include <vector>

#include <glm/vec3.hpp>

#include "beamtree/geometry.h"

namespace sl::sampling {

enum class ClipCase { A, B, C, D, E, F };
const char* to_string(ClipCase c);

struct ClippedTrace {
    ClipCase clip_case = ClipCase::A;
    double start = 0.0;
    double end = 0.0;
    bool sample() const { return clip_case != ClipCase::A && clip_case != ClipCase::F; }
};

ClippedTrace clip_trace(const glm::dvec3& origin, const glm::dvec3& direction, double trace_end,
                        const std::vector<bt::Plane>& volume);

}  // namespace sl::sampling
