// Visibility of the light from a point, through the frame's shadow map (frame/volume_method.h
// ShadowFilter): surfaces and mid-air samples use the same lookup. Needs frame_uniforms.h.
layout(binding = SL_SHADOW_MAP_UNIT) uniform sampler2DShadow shadow_map;
layout(binding = SL_SHADOW_MOMENTS_UNIT) uniform sampler2D shadow_moments;

// VSM: variance floor (in units of the far range squared) and light-bleeding reduction
// (Lauritzen, GPU Gems 3 ch. 8: p_max below this fraction counts as fully shadowed).
const float VSM_MIN_VARIANCE = 1e-8;
const float VSM_BLEEDING_REDUCTION = 0.2;

// The light's linear depth of p: its distance along the axis over the far range, as stored in
// the VSM moments by shadow.vert.
float light_linear_depth(vec3 p) {
    return dot(p - frame.light_position.xyz, frame.light_direction.xyz) / frame.light_direction.w;
}

// 1 where p sees the light, 0 where it does not, fractions in between for filtered maps; 0
// outside the influence pyramid. A pyramid light (light_cone.z = 1) emits up to its sides, where
// a surface's lookup point, moved off the surface by the normal offset, may leave the map: it
// reads the map's edge instead (else the seams between a point light's faces stay dark).
float light_visibility(vec3 p) {
    vec4 clip = frame.light_view_projection * vec4(p, 1.0);
    vec3 coord = 0.5 * clip.xyz / clip.w + 0.5;
    if (frame.light_cone.z > 0.5) {
        coord.xy = clamp(coord.xy, vec2(0.0), vec2(1.0));
    }
    if (clip.w <= 0.0 || any(lessThan(coord, vec3(0.0))) || any(greaterThan(coord, vec3(1.0)))) {
        return 0.0;
    }
    if (frame.shadow.w > 0.5) {
        // Chebyshev's one-sided bound on P(depth >= d) from the blurred moments (VSM).
        float d = light_linear_depth(p);
        vec2 moments = texture(shadow_moments, coord.xy).rg;
        if (d <= moments.x) return 1.0;
        float variance = max(moments.y - moments.x * moments.x, VSM_MIN_VARIANCE);
        float excess = d - moments.x;
        float p_max = variance / (variance + excess * excess);
        return clamp((p_max - VSM_BLEEDING_REDUCTION) / (1.0 - VSM_BLEEDING_REDUCTION), 0.0, 1.0);
    }
    // Hard (r = 0) or PCF: (2r+1)² depth comparisons, each bilinear for the PCF map.
    int radius = int(frame.shadow.y);
    float texel = frame.shadow.x;
    float lit = 0.0;
    for (int y = -radius; y <= radius; ++y) {
        for (int x = -radius; x <= radius; ++x) {
            lit += texture(shadow_map, vec3(coord.xy + vec2(x, y) * texel, coord.z));
        }
    }
    return lit / float((2 * radius + 1) * (2 * radius + 1));
}
