#version 450 core
// The ray-marching buffer brought to full resolution and added into I_s:
//   blur 0  depth-aware bilinear upsampling (a plain copy at full resolution);
//   blur 1  Moschos algorithm 3: the 5x5 Gaussian (σ = 1) of the buffer, depth-blind;
//   blur 2  the same Gaussian weighted by depth similarity (Moschos' future work): no light
//           crosses a depth edge.
// Depth is the distance along each texel's own eye ray to its surface (or the far plane).
#include "sampling/shaders/march_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/view.glsl"

layout(binding = SL_RESOLVE_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(binding = SL_RESOLVE_MARCHED_UNIT) uniform sampler2D marched;
layout(location = SL_RESOLVE_BUFFER_SCALE) uniform float buffer_scale;
layout(location = SL_RESOLVE_BLUR) uniform int blur;
layout(location = 0) out vec4 in_scattered;

const float GAUSS5[25] = float[25](
    0.003765, 0.015019, 0.023792, 0.015019, 0.003765,
    0.015019, 0.059912, 0.094907, 0.059912, 0.015019,
    0.023792, 0.094907, 0.150342, 0.094907, 0.023792,
    0.015019, 0.059912, 0.094907, 0.059912, 0.015019,
    0.003765, 0.015019, 0.023792, 0.015019, 0.003765);
const float DEPTH_TOLERANCE = 0.03;  // relative distance difference of one σ

float distance_at(vec2 fragment) {
    return eye_ray_end(surface_depth, fragment);
}

float depth_weight(ivec2 texel, float pixel_distance) {
    float d = distance_at((vec2(texel) + 0.5) / buffer_scale);
    float relative = (d - pixel_distance) / (DEPTH_TOLERANCE * max(pixel_distance, 1e-3));
    return exp(-0.5 * relative * relative);
}

void main() {
    vec2 pixel = gl_FragCoord.xy;
    ivec2 size = textureSize(marched, 0);
    if (blur == 0 && buffer_scale == 1.0) {
        in_scattered = vec4(texelFetch(marched, ivec2(pixel), 0).rgb, 0.0);
        return;
    }
    float pixel_distance = distance_at(pixel);
    vec3 sum = vec3(0.0);
    float weights = 0.0;
    vec3 nearest = vec3(0.0);
    float nearest_gap = 1.0 / 0.0;
    if (blur == 0) {
        vec2 q = pixel * buffer_scale - 0.5;
        ivec2 base = ivec2(floor(q));
        vec2 f = q - vec2(base);
        for (int j = 0; j <= 1; ++j) {
            for (int i = 0; i <= 1; ++i) {
                ivec2 texel = clamp(base + ivec2(i, j), ivec2(0), size - 1);
                float bilinear = (i == 0 ? 1.0 - f.x : f.x) * (j == 0 ? 1.0 - f.y : f.y);
                float w = bilinear * depth_weight(texel, pixel_distance);
                vec3 value = texelFetch(marched, texel, 0).rgb;
                sum += w * value;
                weights += w;
                float gap = abs(distance_at((vec2(texel) + 0.5) / buffer_scale) - pixel_distance);
                if (gap < nearest_gap) { nearest_gap = gap; nearest = value; }
            }
        }
    } else {
        ivec2 centre = ivec2(floor(pixel * buffer_scale));
        for (int j = -2; j <= 2; ++j) {
            for (int i = -2; i <= 2; ++i) {
                ivec2 texel = clamp(centre + ivec2(i, j), ivec2(0), size - 1);
                float w = GAUSS5[(j + 2) * 5 + (i + 2)];
                if (blur == 2 || buffer_scale < 1.0) w *= depth_weight(texel, pixel_distance);
                vec3 value = texelFetch(marched, texel, 0).rgb;
                sum += w * value;
                weights += w;
                float gap = abs(distance_at((vec2(texel) + 0.5) / buffer_scale) - pixel_distance);
                if (gap < nearest_gap) { nearest_gap = gap; nearest = value; }
            }
        }
    }
    // No neighbour at this pixel's depth: take the closest in depth rather than bleed.
    in_scattered = vec4(weights > 1e-4 ? sum / weights : nearest, 0.0);
}
