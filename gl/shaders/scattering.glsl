// The integrand e(z) of Nilsson eq. 2.7 at one point, GLSL twin of analytic::scattering_density
// and analytic::phase (tested against them): what the sampling methods evaluate per sample.
// Needs frame_uniforms.h and lighting.glsl; included once however often it is named.
#ifndef SL_SCATTERING_GLSL
#define SL_SCATTERING_GLSL

// p(cos α) with asymmetry g, normalised over the sphere; the ids follow scenes/scene.h's
// PhaseFunction.
float phase_function_g(float cos_alpha, float g) {
    int id = int(frame.medium_sigma_s.w + 0.5);
    float c = cos_alpha;
    const float INV_4PI = 0.25 / PI;
    if (id == 1) {  // Henyey-Greenstein, Moschos eq. 2.2
        return INV_4PI * (1.0 - g * g) / pow(1.0 + g * g - 2.0 * g * c, 1.5);
    }
    if (id == 2) {  // Schlick, Moschos eq. 2.3 (sign and |k| as analytic/phase_functions.h)
        float k = clamp(1.55 * g - 0.55 * g * g * g, -0.999, 0.999);
        float d = 1.0 - k * c;
        return INV_4PI * (1.0 - k * k) / (d * d);
    }
    if (id == 3) return 3.0 / (16.0 * PI) * (1.0 + c * c);                   // Rayleigh, eq. 2.4
    if (id == 4) return INV_4PI * (0.5 + 4.5 * pow(0.5 * (1.0 + c), 8.0));    // Mie hazy, eq. 2.5
    if (id == 5) return INV_4PI * (0.5 + 16.5 * pow(0.5 * (1.0 + c), 32.0));  // Mie murky, eq. 2.6
    if (id == 6) return 0.125 / PI * (1.0 + 9.0 * pow(0.5 * (1.0 + c), 8.0));  // Nishita, eq. 2.4
    return INV_4PI;                                                            // isotropic
}

float phase_function(float cos_alpha) {
    return phase_function_g(cos_alpha, frame.medium_attenuation.w);
}

// e(t) per channel at distance t along the ray (origin, direction), visibility excluded: the
// cone factor (eq. 2.9 or the smooth edge), the near/far range, and either model:
//   simplified  σs p I(Ω) / (a1 r² + a0)              Nilsson eq. 2.12-2.15
//   physical    T(t) σs p I(Ω) T(r) / r²              Nilsson eq. 2.6-2.8
vec3 scattering_density_g(vec3 origin, vec3 direction, float t, float g) {
    vec3 from_light = origin + t * direction - frame.light_position.xyz;
    float r = length(from_light);
    if (!(r > 0.0) || !in_light_range(from_light)) return vec3(0.0);
    float cone = cone_factor(from_light);
    if (cone == 0.0) return vec3(0.0);
    if (light_parallel()) {
        // Parallel beams: E T(s) along the beams, s the path past the entry plane.
        float p = phase_function_g(-dot(frame.light_direction.xyz, direction), g);
        return transmittance(t) * frame.medium_sigma_s.rgb * p * frame.light_intensity.rgb *
               cone * light_attenuation(from_light);
    }
    float p = phase_function_g(-dot(from_light / r, direction), g);
    vec3 source = frame.medium_sigma_s.rgb * p * frame.light_intensity.rgb * cone;
    if (frame.medium_sigma_t.w < 0.5) {
        return source / (frame.medium_attenuation.y * r * r + frame.medium_attenuation.x);
    }
    return exp(-frame.medium_sigma_t.rgb * (t + r)) * source / (r * r);
}

vec3 scattering_density(vec3 origin, vec3 direction, float t) {
    return scattering_density_g(origin, direction, t, frame.medium_attenuation.w);
}

#endif  // SL_SCATTERING_GLSL
