#version 450 core
// Copies an 8-bit display image (already tone mapped and sRGB encoded) to the window.
layout(binding = 0) uniform sampler2D source;
in vec2 uv;
layout(location = 0) out vec4 color;
void main() {
    color = vec4(texture(source, uv).rgb, 1.0);
}
