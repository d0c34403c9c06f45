#version 450 core
// Passes the valid samples of splat_light.vert on as points on the 1x1 target.
layout(points) in;
layout(points, max_vertices = 1) out;
in SampleData {
    vec3 position;
    vec3 normal;
    vec3 weight;
    float thickness_mm;
    float footprint_mm;  // radius of the patch the sample stands for
    float valid;
} sample_in[];
out SampleArea {
    float area;
} sample_out;
void main() {
    if (sample_in[0].valid < 0.5) {
        return;
    }
    sample_out.area = sample_in[0].weight.x;  // the vertex shader's area in this mode
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
    EmitVertex();
    EndPrimitive();
}
