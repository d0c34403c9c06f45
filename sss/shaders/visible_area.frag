#version 450 core
// Σ ΔA and the count of valid samples for the seed's A_vis / N_s (eq. 4.6), blended into 1x1.
in SampleArea {
    float area;
} sample_in;
layout(location = 0) out vec4 sums;
void main() {
    sums = vec4(sample_in.area, 1.0, 0.0, 0.0);
}
