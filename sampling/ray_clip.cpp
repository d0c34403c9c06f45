#include "sampling/ray_clip.h"

#include <algorithm>
#include <limits>

#include <glm/geometric.hpp>

namespace sl::sampling {

const char* to_string(ClipCase c) {
    static const char* names[] = {"A", "B", "C", "D", "E", "F"};
    return names[int(c)];
}

ClippedTrace clip_trace(const glm::dvec3& origin, const glm::dvec3& direction, double trace_end,
                        const std::vector<bt::Plane>& volume) {
    // Cyrus-Beck: the line's parameter range inside every half-space.
    double enter = -std::numeric_limits<double>::infinity();
    double exit = std::numeric_limits<double>::infinity();
    for (const bt::Plane& plane : volume) {
        const double distance = plane.distance(origin);
        const double rate = glm::dot(plane.normal, direction);
        if (rate == 0.0) {
            if (distance > 0.0)
                return {ClipCase::A, 0.0, 0.0};
            continue;
        }
        const double t = -distance / rate;
        if (rate < 0.0)
            enter = std::max(enter, t);
        else
            exit = std::min(exit, t);
    }
    if (!(exit > enter) || exit <= 0.0)
        return {ClipCase::A, 0.0, 0.0};
    if (enter <= 0.0) {  // one intersection: the trace starts inside
        return exit < trace_end ? ClippedTrace{ClipCase::B, 0.0, exit}
                                : ClippedTrace{ClipCase::C, 0.0, trace_end};
    }
    if (exit < trace_end)
        return {ClipCase::D, enter, exit};
    if (enter < trace_end)
        return {ClipCase::E, enter, trace_end};
    return {ClipCase::F, 0.0, 0.0};
}

}  // namespace sl::sampling
