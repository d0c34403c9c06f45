// The march of one slice's eye ray along the slice's rectified shadow-map line (Chen, Baran,
// Durand & Jarosz 2011, §4-5; Yusov 2013, §3). The line's depths are level 0 of its min-max tree
// (line_depth); `minmax` holds the levels above, a row per slice: level l (its texels' minimum and
// maximum over 2^l texels) starts at column W - 2W / 2^l. A sample's visibility is the depth test of the texel its point projects to
// (map_visible): the plain march of the rectified map. With minmax_levels > 0 the march walks
// the tree instead: from sample i, the samples in the same node of level l form a run; their
// depths lie between those of its first and last sample (the ray's light depth is monotone in
// t), so a run entirely in front of the node's minimum is lit, one entirely behind its maximum is
// dark, and either is taken at once; otherwise the walk descends, and at level 0 tests each
// sample. After a run it climbs a level. The same samples are lit as in the plain march, and
// their densities are added in the same order: the two sums are equal to the last bit.
// With EPIPOLAR_CLOSED_FORM a lit run adds G(z1) - G(z0) over its steps instead (Chen et al.'s
// analytic lit segments; analytic/shaders/in_scattering.glsl).
// Needs epipolar.glsl.

#include "epipolar/shaders/epipolar_interface.h"

layout(binding = SL_EPIPOLAR_TREE_UNIT) uniform sampler2D minmax;

struct MapPoint {
    float u;  // along the line, in texels
    float z;  // the light's window depth, as the shadow map's comparison takes it
};

MapPoint map_point(vec3 p, vec4 line) {
    vec4 clip = frame.light_view_projection * vec4(p, 1.0);
    vec3 coord = 0.5 * clip.xyz / clip.w + 0.5;
    MapPoint m;
    m.u = dot(coord.xy - line.xy, line.zw) / dot(line.zw, line.zw);
    m.z = clip.w > 0.0 ? coord.z : 2.0;  // behind the light: never lit
    return m;
}

int map_texel(MapPoint m) {
    return m.u >= 0.0 && m.u < float(map_texels) ? int(m.u) : -1;
}

// The plain march's depth test: lit where the point is in the map's depth range and in front of
// (or at) its texel's depth, as GL_LEQUAL compares.
bool map_visible(MapPoint m, int texel, int slice) {
    return texel >= 0 && m.z >= 0.0 && m.z <= 1.0 && m.z <= line_depth(texel, slice);
}

// t at which the ray's u reaches `u`: u(t) = (a + b t) / (c + d t) is projective in t.
struct RayMap {
    float a, b, c, d;
};

RayMap ray_map(vec3 origin, vec3 direction, vec4 line) {
    vec4 o = frame.light_view_projection * vec4(origin, 1.0);
    vec4 v = frame.light_view_projection * vec4(direction, 0.0);
    vec2 e = line.zw / dot(line.zw, line.zw);
    // coord.xy - origin = (0.5 clip.xy + (0.5 - line.xy) clip.w) / clip.w
    RayMap r;
    r.a = dot(0.5 * o.xy + (0.5 - line.xy) * o.w, e);
    r.b = dot(0.5 * v.xy + (0.5 - line.xy) * v.w, e);
    r.c = o.w;
    r.d = v.w;
    return r;
}

float ray_map_inverse(RayMap r, float u) {
    float denominator = r.b - u * r.d;
    return denominator != 0.0 ? (u * r.c - r.a) / denominator : 1e30;
}

vec3 sample_density_at(vec3 origin, vec3 direction, float t) {
    return scattering_density_g(origin, direction, t, frame.medium_attenuation.w);
}

// rgb: I_s over the ray's interval in the cone up to end_distance; a: samples whose density was
// evaluated; lookups (out): texels of the tree read.
vec4 march_rectified(vec3 origin, vec3 direction, float end_distance, int slice, out int lookups) {
    lookups = 0;
    vec4 line = slices[slice].line;
    vec2 cone = light_interval(origin, direction, end_distance);
    float start = cone.x, end = cone.y;
    if (!(end > start) || line.zw == vec2(0.0)) return vec4(0.0);
    float step_length = (end - start) / float(samples);
    vec3 sum = vec3(0.0);
#ifdef EPIPOLAR_CLOSED_FORM
    LightSpans spans = light_spans(origin, direction);
    vec3 closed = vec3(0.0);
#endif
    int taken = 0;
    if (minmax_levels == 0) {
        for (int i = 0; i < samples; ++i) {
            float t = start + (float(i) + 0.5) * step_length;
            MapPoint m = map_point(origin + t * direction, line);
            ++lookups;
            if (!map_visible(m, map_texel(m), slice)) continue;
            ++taken;
            sum += sample_density_at(origin, direction, t);
        }
        return vec4(sum * step_length, float(taken));
    }
    RayMap r = ray_map(origin, direction, line);
    bool increasing = r.b * r.c - r.a * r.d >= 0.0;
    int level = 0;
    int i = 0;
    while (i < samples) {
        float t = start + (float(i) + 0.5) * step_length;
        MapPoint m = map_point(origin + t * direction, line);
        int texel = map_texel(m);
        if (texel < 0) {  // outside the map: dark, as in the plain march
            ++i;
            continue;
        }
        // The run of the node of `level` about texel: samples i..j.
        int first = (texel >> level) << level, last = first + (1 << level);
        float boundary = ray_map_inverse(r, float(increasing ? last : first));
        int j = samples - 1;
        if (boundary > t && boundary < end) {
            j = clamp(int(ceil((boundary - start) / step_length - 0.5)) - 1, i, samples - 1);
        }
        MapPoint mj = map_point(origin + (start + (float(j) + 0.5) * step_length) * direction, line);
        int tj = map_texel(mj);
        while (j > i && (tj < first || tj >= last)) {
            --j;
            mj = map_point(origin + (start + (float(j) + 0.5) * step_length) * direction, line);
            tj = map_texel(mj);
        }
        float z_min = min(m.z, mj.z), z_max = max(m.z, mj.z);
        // Inside a run the depths of the samples between its ends can differ from the exact
        // monotone values by rounding: a margin keeps the run's verdict that of every sample.
        float margin = j > i ? 2.5e-7 : 0.0;
        vec2 node = level == 0 ? vec2(line_depth(texel, slice))
                               : texelFetch(minmax, ivec2(map_texels - ((2 * map_texels) >> level) +
                                                              (texel >> level), slice), 0).rg;
        ++lookups;
        bool lit = z_min >= margin && z_max <= 1.0 - margin && z_max + margin <= node.x;
        bool dark = z_min > node.y + margin || z_min > 1.0 + margin;
        if (lit || dark) {
            if (lit) {
                taken += j - i + 1;
#ifdef EPIPOLAR_CLOSED_FORM
                closed += in_scattering_integral(origin, direction, spans,
                                                 start + float(j + 1) * step_length) -
                          in_scattering_integral(origin, direction, spans,
                                                 start + float(i) * step_length);
#else
                for (int s = i; s <= j; ++s) {
                    sum += sample_density_at(origin, direction,
                                             start + (float(s) + 0.5) * step_length);
                }
#endif
            }
            i = j + 1;
            level = min(level + 1, minmax_levels);
            continue;
        }
        if (level > 0) {
            --level;
            continue;
        }
        // Level 0 and undecided: each sample of the texel on its own.
        for (int s = i; s <= j; ++s) {
            float ts = start + (float(s) + 0.5) * step_length;
            MapPoint ms = s == i ? m : map_point(origin + ts * direction, line);
            if (!map_visible(ms, map_texel(ms), slice)) continue;
            ++taken;
            sum += sample_density_at(origin, direction, ts);
        }
        i = j + 1;
    }
#ifdef EPIPOLAR_CLOSED_FORM
    return vec4(sum * step_length + closed, float(taken));
#else
    return vec4(sum * step_length, float(taken));
#endif
}
