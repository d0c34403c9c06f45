// The spot light and medium terms of the surface pass, mirroring scenes/scene.cpp (SpotLight and
// Medium): the GPU and CPU paths must agree.
const float PI = 3.14159265358979;

// I(Ω)/I: Nilsson eq. 2.9 (hard edge), or a smoothstep over the falloff width inside the edge; a
// pyramid (light_cone.z = 1): 1 inside its four sides, the shadow map's frustum.
float cone_factor(vec3 from_light) {
    if (frame.light_cone.z > 0.5) {
        vec4 clip = frame.light_view_projection * vec4(frame.light_position.xyz + from_light, 1.0);
        return clip.w > 0.0 && max(abs(clip.x), abs(clip.y)) <= clip.w ? 1.0 : 0.0;
    }
    float cos_angle = dot(normalize(from_light), frame.light_direction.xyz);
    float angle = acos(clamp(cos_angle, -1.0, 1.0));
    float half_angle = frame.light_cone.x, falloff = frame.light_cone.y;
    if (falloff <= 0.0) {
        return angle <= half_angle ? 1.0 : 0.0;
    }
    float t = clamp((half_angle - angle) / falloff, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Inside the influence volume along the axis: between the near range and the backplate.
bool in_light_range(vec3 from_light) {
    float axial = dot(from_light, frame.light_direction.xyz);
    return axial >= frame.light_position.w && axial <= frame.light_direction.w;
}

// T(s): e^(-σt s) (Nilsson eq. 2.2) in the physical model, 1 in the simplified one (eq. 2.15).
vec3 transmittance(float s) {
    return frame.medium_sigma_t.w > 0.5 ? exp(-frame.medium_sigma_t.rgb * s) : vec3(1.0);
}

// Parallel beams (a directional light: frame.light_cone.w, its box's half-width, > 0): the light
// travels along the axis everywhere, from the entry plane through light_position.
bool light_parallel() {
    return frame.light_cone.w > 0.0;
}

// The unit direction the light travels at p (from_light = p - light_position).
vec3 light_travel(vec3 from_light) {
    return light_parallel() ? frame.light_direction.xyz : normalize(from_light);
}

// Falloff of the light's intensity with distance r: T(r)/r² (eq. 2.8) or 1/(a1 r² + a0) (eq. 2.13).
vec3 light_falloff(float r) {
    if (frame.medium_sigma_t.w > 0.5) {
        return transmittance(r) / (r * r);
    }
    return vec3(1.0 / (frame.medium_attenuation.y * r * r + frame.medium_attenuation.x));
}

// What reaches p of the light's intensity (I(Ω) or the irradiance), cone aside: light_falloff
// of the distance; for parallel beams T(s) of the path s past the entry plane (1 in the
// simplified model: no attenuation, no falloff).
vec3 light_attenuation(vec3 from_light) {
    if (light_parallel()) return transmittance(dot(from_light, frame.light_direction.xyz));
    return light_falloff(length(from_light));
}
