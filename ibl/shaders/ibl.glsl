// Image-based lighting of the surface pass (ibl/ on the CPU bakes what this reads): the
// prefiltered cube map, SH9 irradiance, and the two shading paths.
//   Moschos algorithms 7-8: the level interpolated from figure 3.24's roughness column, then
//     out = L̄(r, level) · (f_spec(l = r, v) + f_diffuse) · (n·l) · π tan² θ, with Beckmann D
//     (eq. 2.10), Schlick F (eq. 2.11), Beckmann G (eq. 2.12, separable Smith), Lambert
//     (eq. 2.13). The bake stores the cone's cosine-weighted mean L̄; algorithm 6's inv_pdf, the
//     cone's measure π tan² θ, is applied here, so that with h = n, D(n) π tan² θ = tan² θ / α².
//   Split-sum (Karis 2013): L̄(d, √α (L-1)) · (F0 A + B) with the DFG table, d the lobe's dominant
//     direction (Lagarde & de Rousiers 2014), plus Lambert with SH9 irradiance weighted by
//     1 - (F0 A + B).
// Requires frame_uniforms.h and lighting.glsl (PI).
layout(binding = SL_ENVIRONMENT_UNIT) uniform samplerCube environment_map;
layout(binding = SL_DFG_UNIT) uniform sampler2D dfg_table;

bool environment_on() { return frame.environment.x > 0.5; }

// ibl/prefilter.cpp roughness_to_lod, the same mapping as the bake.
float environment_lod(float alpha) {
    float last = frame.environment.z - 1.0;
    if (frame.environment.w < 0.5) {
        return min(sqrt(max(alpha, 0.0)), 1.0) * last;
    }
    for (int l = 0; l < int(last); ++l) {
        float a0 = frame.environment_levels[l].x, a1 = frame.environment_levels[l + 1].x;
        if (alpha <= a1) {
            return float(l) + clamp((alpha - a0) / (a1 - a0), 0.0, 1.0);
        }
    }
    return last;
}

// A per-level quantity interpolated at a fractional level.
vec4 environment_level_at(float lod) {
    int l0 = int(floor(lod));
    int l1 = min(l0 + 1, int(frame.environment.z) - 1);
    return mix(frame.environment_levels[l0], frame.environment_levels[l1], lod - float(l0));
}

// E(n) = Σ Â_l L_lm Y_lm(n) (Ramamoorthi & Hanrahan 2001; ibl/sh9.h's basis).
vec3 sh9_irradiance(vec3 n) {
    const float a0 = PI, a1 = 2.0 * PI / 3.0, a2 = PI / 4.0;
    vec3 e = a0 * 0.282095 * frame.environment_sh9[0].rgb;
    e += a1 * 0.488603 * (n.y * frame.environment_sh9[1].rgb + n.z * frame.environment_sh9[2].rgb +
                          n.x * frame.environment_sh9[3].rgb);
    e += a2 * (1.092548 * n.x * n.y * frame.environment_sh9[4].rgb +
               1.092548 * n.y * n.z * frame.environment_sh9[5].rgb +
               0.315392 * (3.0 * n.z * n.z - 1.0) * frame.environment_sh9[6].rgb +
               1.092548 * n.x * n.z * frame.environment_sh9[7].rgb +
               0.546274 * (n.x * n.x - n.y * n.y) * frame.environment_sh9[8].rgb);
    return max(e, vec3(0.0));
}

vec3 fresnel_schlick(vec3 f0, float v_dot_h) {  // Moschos eq. 2.11
    float c = clamp(1.0 - v_dot_h, 0.0, 1.0);
    return f0 + (1.0 - f0) * (c * c * c * c * c);
}

float beckmann_d(float alpha, float n_dot_h) {  // Moschos eq. 2.10
    float a2 = max(alpha * alpha, 1e-8), c2 = n_dot_h * n_dot_h;
    return exp((c2 - 1.0) / (a2 * c2)) / (PI * a2 * c2 * c2);
}

float beckmann_g1(float alpha, float n_dot_v) {  // Moschos eq. 2.12
    float s = sqrt(max(0.0, 1.0 - n_dot_v * n_dot_v));
    if (s <= 0.0) return 1.0;
    float c = n_dot_v / (max(alpha, 1e-6) * s);
    return c >= 1.6 ? 1.0 : (3.535 * c + 2.181 * c * c) / (1.0 + 2.276 * c + 2.577 * c * c);
}

float ggx_d(float alpha, float n_dot_h) {
    float a2 = max(alpha * alpha, 1e-8);
    float d = (a2 - 1.0) * n_dot_h * n_dot_h + 1.0;
    return a2 / (PI * d * d);
}

float ggx_g2(float alpha, float n_dot_v, float n_dot_l) {  // height-correlated Smith (Heitz 2014)
    float a2 = alpha * alpha;
    float lv = 0.5 * (-1.0 + sqrt(1.0 + a2 * (1.0 - n_dot_v * n_dot_v) / (n_dot_v * n_dot_v)));
    float ll = 0.5 * (-1.0 + sqrt(1.0 + a2 * (1.0 - n_dot_l * n_dot_l) / (n_dot_l * n_dot_l)));
    return 1.0 / (1.0 + lv + ll);
}

// The spot light's specular term f_spec(l, v) (n·l) with the shading path's microfacet model.
vec3 spot_specular(vec3 n, vec3 v, vec3 l, float alpha, vec3 f0) {
    float n_dot_l = dot(n, l), n_dot_v = max(dot(n, v), 1e-4);
    if (n_dot_l <= 0.0) return vec3(0.0);
    vec3 h = normalize(v + l);
    float a = max(alpha, 0.02);  // a point light on a mirror would be a single texel
    bool moschos = frame.environment.y < 0.5;
    float d = moschos ? beckmann_d(a, dot(n, h)) : ggx_d(a, dot(n, h));
    float g = moschos ? beckmann_g1(a, n_dot_v) * beckmann_g1(a, n_dot_l) : ggx_g2(a, n_dot_v, n_dot_l);
    return d * g * fresnel_schlick(f0, dot(v, h)) / (4.0 * n_dot_v);
}

// Outgoing radiance towards v reflected from the environment.
vec3 environment_radiance(vec3 n, vec3 v, vec3 albedo, float alpha, vec3 f0) {
    float n_dot_v = max(dot(n, v), 1e-4);
    vec3 r = reflect(-v, n);
    float lod = environment_lod(alpha);
    vec3 prefiltered = textureLod(environment_map, r, lod).rgb;
    if (frame.environment.y < 0.5) {
        // Moschos algorithms 7-8 with l = r, h = n: n·l = n·v, v·h = n·v.
        vec4 level = environment_level_at(max(lod, 1.0));  // level 0 has no cone: use level 1's
        float g = beckmann_g1(alpha, n_dot_v) * beckmann_g1(alpha, n_dot_v);
        vec3 specular = level.z * fresnel_schlick(f0, n_dot_v) * g / (4.0 * n_dot_v);
        vec3 diffuse = albedo * n_dot_v * level.y;  // albedo/π · (n·l) · π tan² θ
        return frame.environment_options.z * prefiltered * (specular + diffuse);
    }
    // The lobe's dominant direction leans from r towards n as roughness grows (Lagarde & de
    // Rousiers 2014, "Moving Frostbite to PBR", listing 22).
    float smoothness = clamp(1.0 - alpha, 0.0, 1.0);
    vec3 dominant = normalize(mix(n, r, smoothness * (sqrt(smoothness) + alpha)));
    prefiltered = textureLod(environment_map, dominant, lod).rgb;
    // The table's texel centres lie on the ends of its ranges (ibl/microfacet.h DfgTable).
    float texels = float(textureSize(dfg_table, 0).x);
    vec2 coordinate = vec2(min(n_dot_v, 1.0), sqrt(clamp(alpha, 0.0, 1.0)));
    vec2 ab = texture(dfg_table, (coordinate * (texels - 1.0) + 0.5) / texels).rg;
    vec3 specular_weight = f0 * ab.x + ab.y;
    return frame.environment_options.z *
           (prefiltered * specular_weight + albedo / PI * sh9_irradiance(n) * (1.0 - specular_weight));
}
