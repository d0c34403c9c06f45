#version 450 core
// The light volume's edges for the buffer previewer: front faces green, back faces orange.
layout(location = 0) out vec4 color;
void main() {
    color = gl_FrontFacing ? vec4(0.2, 1.0, 0.3, 1.0) : vec4(1.0, 0.55, 0.1, 1.0);
}
