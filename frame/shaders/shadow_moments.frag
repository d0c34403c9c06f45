#version 450 core
// VSM: the first two moments of the light's linear depth (Donnelly & Lauritzen 2006).
in float light_depth;
layout(location = 0) out vec2 moments;
void main() {
    // The second moment gets the depth's variance across the pixel footprint (their §4.2), so
    // that slopes do not shadow themselves.
    float dx = dFdx(light_depth), dy = dFdy(light_depth);
    moments = vec2(light_depth, light_depth * light_depth + 0.25 * (dx * dx + dy * dy));
}
