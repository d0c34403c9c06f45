// The light volume's closed grid (lightvolume/light_volume.h; the CPU twin is
// light_volume_positions): N x N vertices over the light's shadow map, each moved along its light
// ray to the depth the map holds there (the first surface the light meets, or the backplate where
// it meets none), closed by walls down the influence pyramid's sides to the near plane and a fan
// over the near plane. Needs frame_uniforms.h.

#include "lightvolume/shaders/lightvolume_interface.h"
layout(location = SL_LIGHT_VOLUME_RESOLUTION) uniform int grid_resolution;  // N, vertices per side
layout(location = SL_LIGHT_VOLUME_CLIP_TO_WORLD) uniform mat4 light_clip_to_world;  // inverse of frame.light_view_projection
layout(binding = SL_LIGHT_VOLUME_LIGHT_DEPTH_UNIT) uniform sampler2D light_depth;  // the shadow map, read plainly

// Where a vertex of the grid at (i, j) lies: at its shadow-map depth, or on the near plane.
vec3 grid_point(ivec2 ij, bool near_plane) {
    float last = float(grid_resolution - 1);
    vec2 uv = vec2(ij) / last;
    float depth = 0.0;
    if (!near_plane) {
        // The texel whose index is proportional: one per vertex when N equals the map's size.
        int texels = textureSize(light_depth, 0).x;
        ivec2 texel = ivec2(round(vec2(ij) * float(texels - 1) / last));
        depth = texelFetch(light_depth, texel, 0).r;
    }
    vec4 p = light_clip_to_world * vec4(2.0 * uv - 1.0, 2.0 * depth - 1.0, 1.0);
    return p.xyz / p.w;
}

// The k-th grid vertex around the border, counter-clockwise in the map from (0, 0).
ivec2 border_vertex(int k) {
    int n = grid_resolution - 1;
    if (k < n) return ivec2(k, 0);
    if (k < 2 * n) return ivec2(n, k - n);
    if (k < 3 * n) return ivec2(n - (k - 2 * n), n);
    return ivec2(0, n - (k - 3 * n));
}

// The vertex with index `id` (lightvolume::light_volume_triangles numbers them): the N² displaced
// vertices row by row, then the 4(N - 1) border vertices on the near plane, then its centre.
vec3 light_volume_vertex(int id) {
    int n = grid_resolution;
    if (id < n * n) return grid_point(ivec2(id % n, id / n), false);
    int k = id - n * n;
    if (k < 4 * (n - 1)) return grid_point(border_vertex(k), true);
    vec4 p = light_clip_to_world * vec4(0.0, 0.0, -1.0, 1.0);
    return p.xyz / p.w;
}

// True when p lies inside the closed grid: inside the influence pyramid beyond the near plane,
// and nearer the light than the displaced surface along p's light ray (the ray meets that surface
// once, in the triangle over p's place in the map).
bool light_volume_contains(vec3 p) {
    vec4 clip = frame.light_view_projection * vec4(p, 1.0);
    if (!(clip.w > 0.0)) return false;
    vec3 ndc = clip.xyz / clip.w;
    if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z < -1.0) return false;
    vec2 g = (0.5 * ndc.xy + 0.5) * float(grid_resolution - 1);
    ivec2 cell = min(ivec2(g), ivec2(grid_resolution - 2));
    vec2 f = g - vec2(cell);
    // The cell's two triangles, split along its diagonal from (0, 0) to (1, 1).
    vec3 a = grid_point(cell, false), c = grid_point(cell + ivec2(1, 1), false);
    vec3 b = grid_point(cell + (f.x >= f.y ? ivec2(1, 0) : ivec2(0, 1)), false);
    // The ray's start: the light, or for parallel beams p's beam on the entry plane.
    vec3 light = frame.light_position.xyz;
    if (frame.light_cone.w > 0.0) {
        light = p - dot(p - light, frame.light_direction.xyz) * frame.light_direction.xyz;
    }
    vec3 normal = cross(b - a, c - a);
    vec3 ray = p - light;
    float along = dot(ray, normal);
    if (along == 0.0) return true;  // the ray runs inside the surface's plane: take it as inside
    return dot(a - light, normal) / along > 1.0;
}
