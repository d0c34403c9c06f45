// hybrid3's per-pixel uncertain interval [a, b] along the eye ray: the nearest entry into and the
// farthest exit from the uncertain regions (sampling/shaders/uncertain_interval.frag), a = 0 when
// the camera is inside one. Empty (b <= a) where the ray meets none.
layout(binding = 1) uniform sampler2D interval_entry;
layout(binding = 2) uniform sampler2D interval_exit;
layout(binding = 3) uniform sampler2D interval_inside;

vec2 uncertain_interval(ivec2 pixel) {
    float entry = texelFetch(interval_entry, pixel, 0).r;
    float leave = texelFetch(interval_exit, pixel, 0).r;
    bool inside = texelFetch(interval_inside, pixel, 0).r > 0.5;
    return vec2(inside ? 0.0 : entry, leave);
}
