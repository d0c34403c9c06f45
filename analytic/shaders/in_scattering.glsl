// The in-scattering antiderivative G(z) along an eye ray, GLSL twin of analytic/in_scattering.cpp
// (tested against it): E(z0, z1) = G(z1) - G(z0) over the part of the ray inside the exact cone
// and range (Nilsson §3.2.2 adds G on back faces and subtracts it on front faces).
//   simplified, isotropic:   Nilsson eq. 2.17
//   simplified, anisotropic: σs I / (a1 H) R(κ, β), H² = h² + a0/a1, κ = h / H,
//                            β = atan((z - z_s) / H)
//   physical, any phase:     2 σs I e^(-σt z_s) / h · F_p(σt h, ξ), ξ = π/4 + θ/2
// R and F_p are the scene's `medium_table` (analytic/gpu_tables.h: F_p stored as (1 + u) F_p over
// s = u / (1 + u)). A smooth cone edge multiplies the closed form of each of the shell's
// FALLOFF_PIECES pieces by the cone factor at its middle (in_scattering_integral, below). That
// code is compiled only where SL_SMOOTH_CONE_EDGE is defined (a program per edge kind): left in
// behind a uniform branch it made llvmpipe's hard-edge region pass 4.6x slower (134 ms against
// 29 ms on toplight at 640x360).
layout(binding = 7) uniform sampler2D medium_table;

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

// The ray's interval inside a cone of the given half-angle about the light's axis and inside its
// near/far range (as cone_interval).
vec2 cone_interval(vec3 origin, vec3 direction, float t_max, float half_angle) {
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
    if (!(hi > lo) || !(half_angle > 0.0)) return vec2(1.0, 0.0);
    float c = cos(half_angle), c2 = c * c;
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

// The ray's interval inside the light's exact cone and its near/far range (as light_interval).
vec2 light_interval(vec3 origin, vec3 direction, float t_max) {
    return cone_interval(origin, direction, t_max, frame.light_cone.x);
}

// G(z) of the hard edge for the ray (origin, direction), per channel; z is clamped to the cone
// interval `span` so that G(z1) - G(z0) integrates over [z0, z1] ∩ span only.
vec3 in_scattering_antiderivative(vec3 origin, vec3 direction, vec2 span, float z) {
    if (!(span.y > span.x)) return vec3(0.0);
    z = clamp(z, span.x, span.y);
    vec3 delta = frame.light_position.xyz - origin;
    float z_s = dot(delta, direction);
    float h = length(delta - z_s * direction);
    vec3 sigma_s = frame.medium_sigma_s.rgb, intensity = frame.light_intensity.rgb;
    ivec2 last = textureSize(medium_table, 0) - 1;
    if (frame.medium_sigma_t.w < 0.5) {
        float a0 = frame.medium_attenuation.x, a1 = frame.medium_attenuation.y;
        if (frame.medium_attenuation.z > 0.5) {
            // The phase function's integral in β, tabulated (a1 > 0: require_closed_form).
            float H = max(sqrt(h * h + a0 / a1), 1e-6);
            float beta = atan((z - z_s) / H);
            vec2 at = vec2(clamp(h / H, 0.0, 1.0), clamp(beta / PI + 0.5, 0.0, 1.0));
            return sigma_s * intensity / (a1 * H) * table_lookup(medium_table, at * vec2(last));
        }
        // Nilsson eq. 2.17 (as an antiderivative).
        if (a1 == 0.0) return sigma_s * intensity / (4.0 * PI * a0) * z;
        float C = sqrt(a1 * (a1 * h * h + a0));
        return sigma_s * intensity / (4.0 * PI * C) * atan(a1 * (z - z_s) / C);
    }
    // Sun et al. 2005 with the phase function: σt per channel. h > 0 away from the light's axis
    // line. Every point of the ray has z + r >= d (the eye-light distance), so where σt d > 50
    // nothing reaches the eye (e^-50), and e^(-σt z_s) alone could overflow: return 0.
    h = max(h, 1e-6);
    float d = length(delta);
    vec3 sigma_t = frame.medium_sigma_t.rgb;
    float xi = 0.25 * PI + 0.5 * atan((z - z_s) / h);
    vec3 result;
    for (int c = 0; c < 3; ++c) {
        float st = sigma_t[c];
        if (st <= 0.0 || st * d > 50.0) { result[c] = 0.0; continue; }
        float u = st * h;
        vec2 at = vec2(u / (1.0 + u), clamp(xi / (0.5 * PI), 0.0, 1.0));
        float f = table_lookup(medium_table, at * vec2(last)) / (1.0 + u);
        result[c] = 2.0 * sigma_s[c] * intensity[c] * exp(-st * z_s) / h * f;
    }
    return result;
}

// The ray's cone interval and, for a smooth falloff, its inner cone's (half-angle cone -
// falloff, where the factor is 1): `inner` is empty (x = y = outer.y) when there is none.
struct LightSpans {
    vec2 outer, inner;
};

LightSpans light_spans(vec3 origin, vec3 direction) {
    LightSpans spans;
    spans.outer = light_interval(origin, direction, 1e30);
    spans.inner = vec2(spans.outer.y);
#ifdef SL_SMOOTH_CONE_EDGE
    float falloff = frame.light_cone.y;
    if (falloff > 0.0 && spans.outer.y > spans.outer.x) {
        vec2 inner = cone_interval(origin, direction, 1e30, frame.light_cone.x - falloff);
        inner = vec2(max(inner.x, spans.outer.x), min(inner.y, spans.outer.y));
        if (inner.y > inner.x) spans.inner = inner;
    }
#endif
    return spans;
}

#ifdef SL_SMOOTH_CONE_EDGE
// ∫ of e times the cone factor over one shell interval up to z, in FALLOFF_PIECES pieces equal
// in the angle at L (as in_scattering_pieces; edge_defines sets it to kFalloffPieces).
vec3 shell_integral(vec3 origin, vec3 direction, vec2 span, vec2 shell, float z) {
    if (!(shell.y > shell.x) || z <= shell.x) return vec3(0.0);
    vec3 delta = frame.light_position.xyz - origin;
    float z_s = dot(delta, direction);
    float h = max(length(delta - z_s * direction), 1e-6);
    float t0 = atan((shell.x - z_s) / h), t1 = atan((shell.y - z_s) / h);
    vec3 sum = vec3(0.0);
    vec3 previous = in_scattering_antiderivative(origin, direction, span, shell.x);
    for (int k = 0; k < FALLOFF_PIECES; ++k) {
        float ta = t0 + (t1 - t0) * float(k) / float(FALLOFF_PIECES);
        float tb = t0 + (t1 - t0) * float(k + 1) / float(FALLOFF_PIECES);
        float b = k + 1 == FALLOFF_PIECES ? shell.y : z_s + h * tan(tb);
        float end = min(z, b);
        vec3 current = in_scattering_antiderivative(origin, direction, span, end);
        float middle = z_s + h * tan(0.5 * (ta + tb));
        sum += cone_factor(origin + middle * direction - frame.light_position.xyz) *
               (current - previous);
        previous = current;
        if (z <= b) break;
    }
    return sum;
}

#endif

// G(z) of the scene's light, the smooth falloff included: G(z1) - G(z0) = ∫ e c over [z0, z1].
// A program made without SL_SMOOTH_CONE_EDGE integrates a hard edge whatever the uniforms say.
vec3 in_scattering_integral(vec3 origin, vec3 direction, LightSpans spans, float z) {
#ifndef SL_SMOOTH_CONE_EDGE
    return in_scattering_antiderivative(origin, direction, spans.outer, z);
#else
    if (frame.light_cone.y <= 0.0) return in_scattering_antiderivative(origin, direction, spans.outer, z);
    vec3 inner = in_scattering_antiderivative(origin, direction, spans.inner, z) -
                 in_scattering_antiderivative(origin, direction, spans.inner, spans.inner.x);
    return inner + shell_integral(origin, direction, spans.outer, vec2(spans.outer.x, spans.inner.x), z) +
           shell_integral(origin, direction, spans.outer, vec2(spans.inner.y, spans.outer.y), z);
#endif
}
