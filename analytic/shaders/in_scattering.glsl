// The in-scattering antiderivative G(z) along an eye ray, GLSL twin of analytic/in_scattering.cpp
// (tested against it): E(z0, z1) = G(z1) - G(z0) over the part of the ray inside the exact cone
// and range (Nilsson §3.2.2 adds G on back faces and subtracts it on front faces).
//   simplified, isotropic: Nilsson eq. 2.17
//   physical, isotropic:   Sun et al. 2005, A0 F(A1, ξ) with F(u, v) = ∫_0^v exp(-u tan ζ) dζ
//                          tabulated in `sun_table` (u in [0, SUN_TABLE_U_MAX], v in [0, π/2])
//   simplified, a0 = 0, anisotropic: σs I / (a1 h) P(θ), P(θ) = ∫_{-π/2}^θ p(-sin t) dt
//                          tabulated per scene in `phase_table` (θ in [-π/2, π/2])
const float SUN_TABLE_U_MAX = 32.0;
const float SUN_TABLE_SIZE = 1024.0;  // samples at u, v = i / (SIZE - 1) of the range, on texel centres
layout(binding = 7) uniform sampler2D sun_table;
const float PHASE_TABLE_SIZE = 1024.0;
layout(binding = 6) uniform sampler2D phase_table;  // 1 row

// Bilinear interpolation of a table in float arithmetic at `texel` (texel units, 0 at the first
// sample's centre). The texture unit's own GL_LINEAR filter is not used: GPUs interpolate with
// fixed-point weights (8 fractional bits on NVIDIA), which on these smooth tables leaves errors of
// ~1e-4 relative, above what the 1024-sample tables are accurate to.
float table_lookup(sampler2D table, vec2 texel) {
    ivec2 last = textureSize(table, 0) - 1;
    vec2 x = clamp(texel, vec2(0.0), vec2(last));
    ivec2 i = min(ivec2(x), max(last - 1, ivec2(0)));
    vec2 f = x - vec2(i);
    ivec2 j = min(i + 1, last);
    float a = mix(texelFetch(table, i, 0).r, texelFetch(table, ivec2(j.x, i.y), 0).r, f.x);
    float b = mix(texelFetch(table, ivec2(i.x, j.y), 0).r, texelFetch(table, j, 0).r, f.x);
    return mix(a, b, f.y);
}

// The ray's interval inside the light's exact cone and its near/far range (as light_interval).
vec2 light_interval(vec3 origin, vec3 direction, float t_max) {
    vec3 a = frame.light_direction.xyz;
    vec3 w = origin - frame.light_position.xyz;
    float near = frame.light_position.w, far = frame.light_direction.w;
    float lo = 0.0, hi = t_max;
    float da = dot(direction, a), wa = dot(w, a);
    if (abs(da) < 1e-9) {
        if (wa < near || wa > far) return vec2(1.0, 0.0);
    } else {
        float t0 = (near - wa) / da, t1 = (far - wa) / da;
        lo = max(lo, min(t0, t1));
        hi = min(hi, max(t0, t1));
    }
    if (!(hi > lo)) return vec2(1.0, 0.0);
    float c = cos(frame.light_cone.x), c2 = c * c;
    float A = da * da - c2;
    float B = 2.0 * (da * wa - c2 * dot(direction, w));
    float C = wa * wa - c2 * dot(w, w);
    if (abs(A) < 1e-7) {
        if (abs(B) < 1e-30) return C >= 0.0 ? vec2(lo, hi) : vec2(1.0, 0.0);
        float root = -C / B;
        if (B > 0.0) lo = max(lo, root); else hi = min(hi, root);
        return vec2(lo, hi);
    }
    float disc = B * B - 4.0 * A * C;
    if (disc < 0.0) {
        float m = 0.5 * (lo + hi);
        return (A * m + B) * m + C >= 0.0 ? vec2(lo, hi) : vec2(1.0, 0.0);
    }
    float q = -0.5 * (B + (B >= 0.0 ? sqrt(disc) : -sqrt(disc)));
    float r0 = q / A, r1 = q != 0.0 ? C / q : r0;
    if (r0 > r1) { float t = r0; r0 = r1; r1 = t; }
    if (A < 0.0) return vec2(max(lo, r0), min(hi, r1));
    vec2 before = vec2(lo, min(hi, r0)), after = vec2(max(lo, r1), hi);
    float mb = 0.5 * (before.x + before.y), ma = 0.5 * (after.x + after.y);
    if (before.y > before.x && (A * mb + B) * mb + C >= 0.0) return before;
    if (after.y > after.x && (A * ma + B) * ma + C >= 0.0) return after;
    return vec2(1.0, 0.0);
}

// G(z) for the ray (origin, direction), per channel; z is clamped to the cone interval `span`
// so that G(z1) - G(z0) integrates over [z0, z1] ∩ span only.
vec3 in_scattering_antiderivative(vec3 origin, vec3 direction, vec2 span, float z) {
    if (!(span.y > span.x)) return vec3(0.0);
    z = clamp(z, span.x, span.y);
    vec3 delta = frame.light_position.xyz - origin;
    float z_s = dot(delta, direction);
    float h = length(delta - z_s * direction);
    vec3 sigma_s = frame.medium_sigma_s.rgb, intensity = frame.light_intensity.rgb;
    if (frame.medium_sigma_t.w < 0.5 && frame.medium_attenuation.z > 0.5) {
        // dz / r² = dθ / h and cos α = -sin θ: the phase function's integral over θ, tabulated.
        float theta = atan((z - z_s) / max(h, 1e-6));
        float at = clamp(theta / PI + 0.5, 0.0, 1.0);
        float p = table_lookup(phase_table, vec2(at * (PHASE_TABLE_SIZE - 1.0), 0.0));
        return sigma_s * intensity / (frame.medium_attenuation.y * max(h, 1e-6)) * p;
    }
    if (frame.medium_sigma_t.w < 0.5) {
        // Nilsson eq. 2.17 (as an antiderivative).
        float a0 = frame.medium_attenuation.x, a1 = frame.medium_attenuation.y;
        if (a1 == 0.0) return sigma_s * intensity / (4.0 * PI * a0) * z;
        float C = sqrt(a1 * (a1 * h * h + a0));
        return sigma_s * intensity / (4.0 * PI * C) * atan(a1 * (z - z_s) / C);
    }
    // Sun et al. 2005: A0 F(A1, ξ(z)); σt per channel. h > 0 away from the light's axis line.
    h = max(h, 1e-6);
    vec3 sigma_t = frame.medium_sigma_t.rgb;
    float xi = 0.25 * PI + 0.5 * atan((z - z_s) / h);
    vec3 result;
    for (int c = 0; c < 3; ++c) {
        float st = sigma_t[c];
        if (st <= 0.0) { result[c] = 0.0; continue; }
        float A0 = sigma_s[c] * intensity[c] * exp(-st * z_s) / (2.0 * PI * h);
        float A1 = st * h;
        vec2 at = vec2(clamp(A1 / SUN_TABLE_U_MAX, 0.0, 1.0), clamp(xi / (0.5 * PI), 0.0, 1.0));
        float f = table_lookup(sun_table, at * (SUN_TABLE_SIZE - 1.0));
        result[c] = A0 * f;
    }
    return result;
}
