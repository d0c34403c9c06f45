#version 450 core
// Depth only: the shadow map is the depth attachment.
void main() {}
