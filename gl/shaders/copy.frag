#version 450 core
// Writes a texture computed elsewhere (e.g. the CPU reference's I_s) into the bound target.
layout(binding = 0) uniform sampler2D source;
in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    color = vec4(texelFetch(source, ivec2(gl_FragCoord.xy), 0).rgb, 1.0);
}
