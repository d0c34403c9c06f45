// The in-scattering antiderivative G(z) along an eye ray, GLSL twin of analytic/in_scattering.cpp
// (tested against it and against quadrature): E(z0, z1) = G(z1) - G(z0) over the part of the ray
// inside the exact cone and range (Nilsson §3.2.2 adds G on back faces and subtracts it on front
// faces).
//   simplified, isotropic:   Nilsson eq. 2.17
//   simplified, anisotropic: σs I / (a1 H) R(κ, β), H² = h² + a0/a1, κ = h / H,
//                            β = atan((z - z_s) / H)
//   physical, any phase:     2 σs I e^(-σt z_s) / h · F_p(σt h, ζ), ζ = π/4 + θ/2, and past the
//                            closest approach its tail 2 σs I e^(-σt (z + r)) T / (q (1 + σt q))
// R, F_p, T and R's complement are the scene's `medium_table` (analytic/gpu_tables.h). A smooth
// cone edge multiplies the closed form of each of the shell's
// FALLOFF_PIECES pieces by the cone factor at its middle (in_scattering_integral, below). That
// code is compiled only where SL_SMOOTH_CONE_EDGE is defined (a program per edge kind): left in
// behind a uniform branch it made llvmpipe's hard-edge region pass 4.6x slower (134 ms against
// 29 ms on toplight at 640x360).
#include "analytic/shaders/analytic_interface.h"
#include "gl/shaders/scattering.glsl"
layout(binding = SL_MEDIUM_TABLE_UNIT) uniform sampler2D medium_table;

// Bilinear interpolation of one channel of a table in float arithmetic at `texel` (texel units, 0
// at the first sample's centre). The texture unit's own GL_LINEAR filter is not used: GPUs
// interpolate with fixed-point weights (8 fractional bits on NVIDIA), which on these smooth tables
// leaves errors of ~1e-4 relative, above what the tables are accurate to.
// Row y of a table, linearly interpolated at x (texel units), one channel.
float table_row(sampler2D table, float x, int y, int channel) {
    int last = textureSize(table, 0).x - 1;
    x = clamp(x, 0.0, float(last));
    int i = min(int(x), max(last - 1, 0));
    return mix(texelFetch(table, ivec2(i, y), 0)[channel],
               texelFetch(table, ivec2(min(i + 1, last), y), 0)[channel], x - float(i));
}

float table_lookup(sampler2D table, vec2 texel, int channel) {
    int last = textureSize(table, 0).y - 1;
    float y = clamp(texel.y, 0.0, float(last));
    int i = min(int(y), max(last - 1, 0));
    return mix(table_row(table, texel.x, i, channel), table_row(table, texel.x, min(i + 1, last), channel),
               y - float(i));
}

// A cumulative table's value at angle w of its y axis (rows `step` apart from w = 0): the row at
// the node below w, interpolated in x only, is exact in w; the rest of the cell, [node, w], is
// added by 3-point Gauss-Legendre of the integrand the table sums. Linear interpolation in w would
// stand for the integrand by its mean over the cell, which on a short lit piece near a phase
// function's peak (g = 0.9: 1.2e-2 relative) is far from its value there.
const float GAUSS3_NODE = 0.7745966692, GAUSS3_OUTER = 5.0 / 9.0, GAUSS3_INNER = 8.0 / 9.0;

// F_p(u, ζ) = ∫_0^ζ e^(-u tan ζ') p(cos 2ζ') dζ', the physical model's front channel (stored as
// (1 + u) F_p on s = u / (1 + u)). What is the same for every channel's u is made once: the row
// below ζ, and the Gauss nodes' tan ζ and weighted p(cos 2ζ).
struct FrontCell {
    int row;
    vec3 tangent;
    vec3 weighted;
};

FrontCell front_cell(float zeta, vec2 last) {
    float step = 0.5 * PI / last.y;
    FrontCell cell;
    cell.row = int(min(floor(zeta / step), last.y));
    float node = float(cell.row) * step;
    float half_cell = 0.5 * (zeta - node), mid = node + half_cell, d = GAUSS3_NODE * half_cell;
    vec3 at = vec3(mid - d, mid, mid + d);
    // float(π/2) lies past π/2, where tan turns negative: an empty cell there must add 0.
    cell.tangent = half_cell > 0.0 ? tan(at) : vec3(0.0);
    cell.weighted = half_cell * vec3(GAUSS3_OUTER * phase_function(cos(2.0 * at.x)),
                                     GAUSS3_INNER * phase_function(cos(2.0 * at.y)),
                                     GAUSS3_OUTER * phase_function(cos(2.0 * at.z)));
    return cell;
}

float physical_front(FrontCell cell, float u, vec2 last) {
    return table_row(medium_table, u / (1.0 + u) * last.x, cell.row, 0) / (1.0 + u) +
           dot(cell.weighted, exp(-u * cell.tangent));
}

// The simplified model's integrand in an angle w from one end of β: cos α = ±cos w /
// sqrt(κ² sin² w + cos² w), + from β = -π/2 (w = β + π/2), - from β = π/2 (w = π/2 - β).
float simplified_phase(float kappa, float w, float sign) {
    float c = cos(w), s = kappa * sin(w);
    return phase_function(sign * c / max(sqrt(s * s + c * c), 1e-30));
}

float simplified_cell(float kappa, float a, float b, float sign) {
    float half_cell = 0.5 * (b - a), mid = a + half_cell, d = GAUSS3_NODE * half_cell;
    return half_cell * (GAUSS3_OUTER * (simplified_phase(kappa, mid - d, sign) +
                                        simplified_phase(kappa, mid + d, sign)) +
                        GAUSS3_INNER * simplified_phase(kappa, mid, sign));
}

// R from one end of β to the angle w from it: channel 0 from β = -π/2 (sign +1), channel 1, its
// complement, from β = π/2 (sign -1). cos α turns over a width κ about β = 0 (w = π/2): the
// cell's rest is split there.
float simplified_cumulative(float kappa, float w, int channel, float sign, vec2 last) {
    float step = PI / last.y;
    int row = int(min(floor(w / step), last.y));
    float node = float(row) * step;
    float r = table_row(medium_table, kappa * last.x, row, channel);
    if (w > node) {
        float middle = 0.5 * PI;
        if (node < middle && middle < w) {
            r += simplified_cell(kappa, node, middle, sign) + simplified_cell(kappa, middle, w, sign);
        } else {
            r += simplified_cell(kappa, node, w, sign);
        }
    }
    return r;
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

// Clips [lo, hi] to where a + b t >= 0 (as in_scattering.cpp's clip_linear).
vec2 clip_linear(float a, float b, vec2 span) {
    if (b == 0.0) return a >= 0.0 ? span : vec2(1.0, 0.0);
    float root = -a / b;
    return b > 0.0 ? vec2(max(span.x, root), span.y) : vec2(span.x, min(span.y, root));
}

// The ray's interval inside a pyramid light's four sides and its near/far range (as
// pyramid_interval): each side is a plane of the shadow map's clip space, w ± x >= 0, w ± y >= 0.
vec2 pyramid_interval(vec3 origin, vec3 direction, float t_max) {
    vec3 a = frame.light_direction.xyz;
    vec3 w = origin - frame.light_position.xyz;
    float near = frame.light_position.w, far = frame.light_direction.w;
    float wa = dot(w, a), va = dot(direction, a);
    vec2 span = clip_linear(wa - near, va, vec2(0.0, t_max));
    span = clip_linear(far - wa, -va, span);
    mat4 m = transpose(frame.light_view_projection);  // rows of the light's clip transform
    vec4 o = vec4(origin, 1.0), d = vec4(direction, 0.0);
    for (int k = 0; k < 4; ++k) {
        vec4 plane = m[3] + (k % 2 == 0 ? 1.0 : -1.0) * m[k / 2];
        span = clip_linear(dot(plane, o), dot(plane, d), span);
    }
    return span.y > span.x ? span : vec2(1.0, 0.0);
}

// The ray's interval inside the light's exact cone (or pyramid) and its near/far range (as
// light_interval).
vec2 light_interval(vec3 origin, vec3 direction, float t_max) {
    if (frame.light_cone.z > 0.5) return pyramid_interval(origin, direction, t_max);
    return cone_interval(origin, direction, t_max, frame.light_cone.x);
}

// G(z) of the hard edge, in the three forms below; each is given the ray's closest approach to the
// light (z_s along the ray, h away from it), x = z - z_s, d = |L - origin| and whether G is
// anchored at the ray's far end.
//
// Where G is anchored (its zero) is the ray's, never the point's, so that every fragment of a ray
// adds and subtracts the same function; it is chosen so that G stays of the size of what is
// integrated (analytic/in_scattering.h, "Conditioning"):
//   span beyond the closest approach (z_s <= span.x; every ray that points away from the light):
//       anchored at z = +∞, from the tables' far-end channel;
//   otherwise (toward the light, or across the closest approach, where h >= near):
//       anchored at z = -∞.
// The angles are taken with atan2 of (h or H, ±x), which keeps their digits where they approach
// 0 or π (an angle in [0, π] written as π/2 + atan(x / h) loses them to the π/2).

// Nilsson eq. 2.17 (as an antiderivative): atan(a1 x / C) + π/2 = atan2(C, -a1 x), and
// atan(a1 x / C) - π/2 = -atan2(C, a1 x).
vec3 simplified_isotropic_antiderivative(float z, float x, float h, bool far_anchor) {
    vec3 source = frame.medium_sigma_s.rgb * frame.light_intensity.rgb;
    float a0 = frame.medium_attenuation.x, a1 = frame.medium_attenuation.y;
    if (a1 == 0.0) return source / (4.0 * PI * a0) * z;
    float C = max(sqrt(a1 * (a1 * h * h + a0)), 1e-30);
    float angle = far_anchor ? -atan(C, a1 * x) : atan(C, -a1 * x);
    return source / (4.0 * PI * C) * angle;
}

// σs I / (a1 H) R(κ, β): the phase function's integral in β, tabulated (a1 > 0:
// require_closed_form), R from β = -π/2 in the first channel, its complement from β = π/2 in the
// second.
vec3 simplified_table_antiderivative(float x, float h, bool far_anchor) {
    vec3 source = frame.medium_sigma_s.rgb * frame.light_intensity.rgb;
    float a0 = frame.medium_attenuation.x, a1 = frame.medium_attenuation.y;
    vec2 last = vec2(textureSize(medium_table, 0) - 1);
    float H = max(sqrt(h * h + a0 / a1), 1e-6);
    float kappa = clamp(h / H, 0.0, 1.0);
    if (far_anchor) {
        return -source / (a1 * H) * simplified_cumulative(kappa, atan(H, x), 1, -1.0, last);
    }
    return source / (a1 * H) * simplified_cumulative(kappa, atan(H, -x), 0, 1.0, last);
}

// Sun et al. 2005 with the phase function, in in_scattering.h's forms: G / (2 σs I) for one σt.
// Every point of the ray has z + r >= d (the eye-light distance), so where σt d > 50 nothing
// reaches the eye (e^-50): 0.
float physical_shape(float st, float z, float z_s, float x, float h, float d, float r, float q,
                     FrontCell cell, bool far_anchor, vec2 last) {
    if (st <= 0.0 || st * d > 50.0) return 0.0;
    // The tail ∫_z^∞ e dz / (2 σs I) = e^(-σt (z + r)) T / (q (1 + σt q)), T on
    // (sqrt(h / q), sqrt(s / (1 + s))), s = σt q.
    float tail = 0.0;
    if (x >= 0.0) {
        float s = st * q;
        vec2 at = vec2(sqrt(h / q), sqrt(s / (1.0 + s)));
        tail = exp(-st * (z + r)) * table_lookup(medium_table, at * last, 1) / (q * (1.0 + s));
        if (far_anchor) return -tail;
    }
    // e^(-σt z_s) / h · F_p(σt h, ζ) from ζ = 0 (z = -∞); past the closest approach, the whole
    // line's less the tail.
    return exp(-st * z_s) / h * physical_front(cell, st * h, last) - tail;
}

// The physical model's G per channel. A grey medium (σt the same in every channel, as most are)
// has one shape for all three.
vec3 physical_antiderivative(float z, float z_s, float x, float h, float d, bool far_anchor) {
    vec2 last = vec2(textureSize(medium_table, 0) - 1);
    h = max(h, 1e-6);
    float r = sqrt(x * x + h * h);
    // q = x + r = h tan ζ, written without cancellation on either side of the closest approach.
    float q = x >= 0.0 ? x + r : h * h / (r - x);
    vec3 sigma_t = frame.medium_sigma_t.rgb;
    // Past the closest approach the front term is the whole line's, F_p(u, π/2): the table's
    // last row, with no cell left to add (and only the tail where G is anchored at +∞).
    FrontCell cell = x >= 0.0 ? FrontCell(int(last.y), vec3(0.0), vec3(0.0))
                              : front_cell(0.5 * atan(h, -x), last);
    vec3 shape;
    shape.r = physical_shape(sigma_t.r, z, z_s, x, h, d, r, q, cell, far_anchor, last);
    shape.g = sigma_t.g == sigma_t.r
                  ? shape.r
                  : physical_shape(sigma_t.g, z, z_s, x, h, d, r, q, cell, far_anchor, last);
    shape.b = sigma_t.b == sigma_t.r   ? shape.r
              : sigma_t.b == sigma_t.g ? shape.g
                                       : physical_shape(sigma_t.b, z, z_s, x, h, d, r, q, cell,
                                                        far_anchor, last);
    return 2.0 * frame.medium_sigma_s.rgb * frame.light_intensity.rgb * shape;
}

// G(z) of parallel beams (a directional light; in_scattering.cpp's parallel_integral): the
// scattering angle is constant and the path s = wa + z va linear, so e = σs p E e^(-σt (z + s)),
// G(z) = σs p E e^(-σt (z0 + s(z0))) (1 - e^(-k (z - z0))) / k with k = σt (1 + va), anchored at
// the span's start z0 (where both exponents are smallest, so nothing overflows), and a series
// where k (z - z0) is small (no cancellation when the ray runs along the beams).
vec3 parallel_antiderivative(vec3 origin, vec3 direction, vec2 span, float z) {
    vec3 a = frame.light_direction.xyz;
    float va = dot(direction, a);
    vec3 source = frame.medium_sigma_s.rgb * phase_function(-va) * frame.light_intensity.rgb;
    float length_in = z - span.x;
    if (frame.medium_sigma_t.w < 0.5) return source * length_in;
    float s0 = max(dot(origin - frame.light_position.xyz, a) + span.x * va, 0.0);
    vec3 sigma_t = frame.medium_sigma_t.rgb;
    vec3 k = sigma_t * max(1.0 + va, 0.0);
    vec3 x = k * length_in;
    vec3 series = length_in * (1.0 - x * (0.5 - x / 6.0));
    vec3 exact = (1.0 - exp(-x)) / max(k, vec3(1e-30));
    vec3 integral = mix(exact, series, lessThan(x, vec3(1e-3)));
    return source * exp(-sigma_t * (span.x + s0)) * integral;
}

// G(z) of the hard edge for the ray (origin, direction), per channel; z is clamped to the cone
// interval `span` so that G(z1) - G(z0) integrates over [z0, z1] ∩ span only. SL_MEDIUM_FORM
// (closed_form_defines) compiles the scene's form alone: 0 Nilsson eq. 2.17, 1 the simplified
// model's table, 2 the physical model. Without it all three are compiled behind branches on the
// frame's uniforms, which llvmpipe runs every side of (the region pass 2x slower on toplight).
vec3 in_scattering_antiderivative(vec3 origin, vec3 direction, vec2 span, float z) {
    if (!(span.y > span.x)) return vec3(0.0);
    z = clamp(z, span.x, span.y);
    if (light_parallel()) return parallel_antiderivative(origin, direction, span, z);
    vec3 delta = frame.light_position.xyz - origin;
    float z_s = dot(delta, direction);
    float h = length(delta - z_s * direction);
    float x = z - z_s;
    bool far_anchor = z_s <= span.x;
#if !defined(SL_MEDIUM_FORM)
    if (frame.medium_sigma_t.w > 0.5) return physical_antiderivative(z, z_s, x, h, length(delta), far_anchor);
    if (frame.medium_attenuation.z > 0.5) return simplified_table_antiderivative(x, h, far_anchor);
    return simplified_isotropic_antiderivative(z, x, h, far_anchor);
#elif SL_MEDIUM_FORM == 2
    return physical_antiderivative(z, z_s, x, h, length(delta), far_anchor);
#elif SL_MEDIUM_FORM == 1
    return simplified_table_antiderivative(x, h, far_anchor);
#else
    return simplified_isotropic_antiderivative(z, x, h, far_anchor);
#endif
}

// The ray's cone interval and, for a smooth falloff, its inner cone's (half-angle cone -
// falloff, where the factor is 1): `inner` is empty (x = y = outer.y) when there is none. With
// SL_POINT_SHELL (a face of a point light, whose edge is hard): the ray's at most two intervals in
// the point light's whole shell, `outer` the nearer and `inner` the farther (shell_spans).
struct LightSpans {
    vec2 outer, inner;
};

#ifdef SL_POINT_SHELL
// The ray's interval (from 0 to t_max) inside the cube of half-size `half_size` about L, its
// sides along the world's axes as a point light's faces are (PointLight::faces).
vec2 cube_interval(vec3 w, vec3 direction, float half_size, float t_max) {
    vec2 span = vec2(0.0, t_max);
    for (int k = 0; k < 3; ++k) {
        span = clip_linear(half_size - w[k], -direction[k], span);
        span = clip_linear(half_size + w[k], direction[k], span);
    }
    return span;
}

// The ray's intervals between the point light's two cubes (of half-sizes near and far, the
// face's own): what its six faces' pyramids tile. The faces of a point light integrate over the
// whole shell, not their own pyramid, so that G is the same function in all six and the region
// faces on the planes between two faces, which cancel in pairs, can be left out of both
// (AnalyticRegionPass::upload_mesh): a closed region inside the pyramid integrates the same
// with either.
LightSpans shell_spans(vec3 origin, vec3 direction) {
    vec3 w = origin - frame.light_position.xyz;
    float near = frame.light_position.w, far = frame.light_direction.w;
    vec2 outer = cube_interval(w, direction, far, 1e30);
    vec2 inner = cube_interval(w, direction, near, 1e30);
    LightSpans spans;
    spans.outer = vec2(1.0, 0.0);
    spans.inner = vec2(1.0, 0.0);
    if (!(outer.y > outer.x)) return spans;
    if (!(inner.y > inner.x)) {
        spans.outer = outer;
        return spans;
    }
    spans.outer = vec2(outer.x, min(outer.y, inner.x));
    spans.inner = vec2(max(outer.x, inner.y), outer.y);
    return spans;
}
#endif

LightSpans light_spans(vec3 origin, vec3 direction) {
#ifdef SL_POINT_SHELL
    return shell_spans(origin, direction);
#endif
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
// in the angle at L (as in_scattering_pieces; closed_form_defines sets it to kFalloffPieces).
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
#ifdef SL_POINT_SHELL
    return in_scattering_antiderivative(origin, direction, spans.outer, z) +
           in_scattering_antiderivative(origin, direction, spans.inner, z);
#endif
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
