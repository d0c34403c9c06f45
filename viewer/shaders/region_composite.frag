#version 450 core
// The regions drawn as translucent media over the frame (Nilsson figure 5.4's colours: lit
// yellow, uncertain grey, unlit black): optical depth τ_i = k_i L_i per region type from the
// accumulated lengths L_i, α = 1 - e^(-Σ τ_i), colour the τ-weighted mean. Premultiplied alpha.
layout(binding = 0) uniform sampler2D thickness;
layout(location = 0) uniform vec3 density;  // k_i per metre; 0 hides a layer
layout(location = 1) uniform vec3 lit_color;
layout(location = 2) uniform vec3 uncertain_color;
layout(location = 3) uniform vec3 unlit_color;
layout(location = 0) out vec4 color;
void main() {
    vec3 length_in = max(texelFetch(thickness, ivec2(gl_FragCoord.xy), 0).rgb, vec3(0.0));
    vec3 tau = density * length_in;
    float total = tau.x + tau.y + tau.z;
    if (total <= 1e-6) discard;
    float alpha = 1.0 - exp(-total);
    vec3 mean = (tau.x * lit_color + tau.y * uncertain_color + tau.z * unlit_color) / total;
    color = vec4(alpha * mean, alpha);
}
