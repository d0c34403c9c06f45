#version 450 core
// Epipolar pass 7, the unwarp (Engelhardt & Dachsbacher 2010 §3.3; Yusov 2013 §3.5): each pixel
// finds the two slices about it (slice_coordinate) and, on each, the two samples about its
// position, and takes their bilinear blend, each sample weighted 0 when its view depth is not
// the pixel's surface (same_surface): a bilateral filter, so that no shaft bleeds across a depth
// edge. A pixel left without a sample of its surface is marched directly through the frame's
// shadow map (march_direct: Yusov's fix-up pass), as is every pixel with interpolation off.
#include "epipolar/shaders/epipolar_interface.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/shaders/lighting.glsl"
#include "gl/shaders/scattering.glsl"
#include "gl/shaders/shadow.glsl"
#include "gl/shaders/view.glsl"
#include "analytic/shaders/in_scattering.glsl"
#include "epipolar/shaders/epipolar.glsl"

layout(binding = SL_EPIPOLAR_SURFACE_DEPTH_UNIT) uniform sampler2D surface_depth;
layout(binding = SL_EPIPOLAR_COORDINATES_UNIT) uniform sampler2D coordinates;
layout(binding = SL_EPIPOLAR_SCATTERING_UNIT) uniform sampler2D scattering;
layout(location = 0) out vec4 in_scattered;

// The least summed weight of the samples of the pixel's surface that is interpolated.
const float MIN_WEIGHT = 1e-2;

void main() {
    vec2 x = gl_FragCoord.xy;
    vec3 origin = frame.camera_position.xyz;
    vec3 direction = eye_ray_direction(x);
    float end = eye_ray_end(surface_depth, x);
    if (direct == 0) {
        float depth = view_depth(direction, end);
        float c = slice_coordinate(x);
        int s0 = int(floor(c));
        float fs = c - float(s0);
        int s1 = s0 + 1;
        if (arc.z > 0.5) {
            s0 = (s0 % grid.y + grid.y) % grid.y;
            s1 = (s1 % grid.y + grid.y) % grid.y;
        } else if (s0 < 0) {
            s0 = s1 = 0;
        } else if (s1 >= grid.y) {
            s0 = s1 = grid.y - 1;
        }
        vec3 sum = vec3(0.0);
        float total = 0.0;
        for (int n = 0; n < 2; ++n) {
            int s = n == 0 ? s0 : s1;
            float ws = n == 0 ? 1.0 - fs : fs;
            float kf = clamp(sample_coordinate(s, x), 0.0, float(grid.x - 1));
            int k0 = int(floor(kf));
            float fk = kf - float(k0);
            for (int m = 0; m < 2; ++m) {
                int k = min(k0 + m, grid.x - 1);
                float w = ws * (m == 0 ? 1.0 - fk : fk);
                vec4 sample_at = texelFetch(coordinates, ivec2(k, s), 0);
                if (!(w > 0.0) || sample_at.w < 0.0 || !same_surface(sample_at.w, depth)) continue;
                sum += w * texelFetch(scattering, ivec2(k, s), 0).rgb;
                total += w;
            }
        }
        if (total >= MIN_WEIGHT) {
            in_scattered = vec4(sum / total, 0.0);
            return;
        }
    }
    vec4 marched = march_direct(origin, direction, end);
    atomicAdd(fixup_pixels, 1u);
    atomicAdd(fixup_samples, uint(marched.a));
    in_scattered = vec4(marched.rgb, 0.0);
}
