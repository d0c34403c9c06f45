// The distance along a pixel's eye ray to the triangle a fragment belongs to, from the triangle's
// corners (analytic/region_faces.h) rather than its interpolated position: the plane of the
// triangle met by the ray, within the span its corners cover along the ray (where a crossing of
// the triangle must lie). A triangle degenerate in float, or met at a grazing angle, gives the
// point of its longest edge nearest the ray instead, within the same span: a pixel centre that
// the rasterizer gives to such a triangle lies by the edge it shares with the neighbour that
// covers the pixel once more, so the pair's two G(z) nearly cancel, as the exact faces' do.

#include "analytic/shaders/analytic_interface.h"
layout(std430, binding = SL_FACE_CORNERS_BINDING) readonly buffer FaceCorners {
    vec4 face_corners[];
};

float face_distance(vec3 origin, vec3 direction, int triangle) {
    vec3 a = face_corners[3 * triangle].xyz;
    vec3 b = face_corners[3 * triangle + 1].xyz;
    vec3 c = face_corners[3 * triangle + 2].xyz;
    float ta = dot(a - origin, direction), tb = dot(b - origin, direction);
    float tc = dot(c - origin, direction);
    float lo = min(ta, min(tb, tc)), hi = max(ta, max(tb, tc));
    vec3 n = cross(b - a, c - a);
    float facing = dot(n, direction);
    if (abs(facing) > 1e-4 * length(n)) {
        float t = dot(n, a - origin) / facing;
        if (!isnan(t) && !isinf(t)) {
            return clamp(t, lo, hi);
        }
    }
    // The longest edge p -> p + e; its point p + s e nearest the ray origin + t direction.
    vec3 p = a, e = b - a;
    if (dot(c - b, c - b) > dot(e, e)) {
        p = b;
        e = c - b;
    }
    if (dot(a - c, a - c) > dot(e, e)) {
        p = c;
        e = a - c;
    }
    float ee = dot(e, e), de = dot(direction, e);
    vec3 w = origin - p;
    float denominator = ee - de * de;
    float s = denominator > 1e-12 * ee ? clamp((dot(e, w) - dot(direction, w) * de) / denominator,
                                               0.0, 1.0)
                                       : 0.5;
    return clamp(dot(p + s * e - origin, direction), lo, hi);
}
