#version 450 core
// The buffer previewer: one texture (float colour or depth, read without comparison) mapped to
// display values: the chosen channel(s), (v - lo) / (hi - lo), optionally on a log10 scale.
layout(binding = 0) uniform sampler2D source;
layout(location = 0) uniform int channel;  // 0 rgb, 1 r, 2 g, 3 b, 4 a
layout(location = 1) uniform vec2 range;   // lo, hi (log10 of them when logarithmic)
layout(location = 2) uniform int logarithmic;
in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    vec4 texel = texture(source, uv);
    vec3 v = channel == 0 ? texel.rgb : vec3(texel[channel - 1]);
    if (logarithmic != 0) v = log(max(v, vec3(1e-30))) / log(10.0);
    vec3 mapped = clamp((v - range.x) / max(range.y - range.x, 1e-30), 0.0, 1.0);
    // Not-a-number shows magenta, so broken buffers are seen rather than guessed.
    bvec3 nan = isnan(texel.rgb);
    if (any(nan)) mapped = vec3(1.0, 0.0, 1.0);
    color = vec4(pow(mapped, vec3(1.0 / 2.2)), 1.0);
}
