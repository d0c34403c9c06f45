// The beam tree's classify() on the GPU (beamtree/beam_tree.h), reading BeamTree::gpu_tree():
// the near and far ranges, then the descent from the root (front when the distance is >= 0,
// Nilsson Program 2), then the leaf: open lit; solid lit in front of its occluder (distance > 0),
// uncertain behind; blocker also unlit behind its stopper. Planes are relative to the light, so
// float keeps the tree's ε. Needs frame_uniforms.h (the light's position). Tested against the
// C++ classify on 10^5 points.

#include "beamtree/shaders/classify_interface.h"

const int REGION_LIT = 0;
const int REGION_UNCERTAIN = 1;
const int REGION_UNLIT = 2;
const int KIND_SPLIT = 0;
const int KIND_OPEN = 2;
const int KIND_SOLID = 3;
const int KIND_BLOCKER = 4;

struct TreeNode {
    vec4 plane;  // xyz normal, w offset, relative to the light
    ivec4 link;  // front, back, kind, stopper plane index
};
layout(std430, binding = SL_TREE_NODES_BINDING) readonly buffer TreeNodes { TreeNode tree_nodes[]; };
layout(std430, binding = SL_TREE_PLANES_BINDING) readonly buffer TreePlanes { vec4 tree_planes[]; };

float tree_distance(vec4 plane, vec3 q) { return dot(plane.xyz, q) + plane.w; }

// A leaf's region at q (light-relative, inside the near and far ranges): open lit; solid lit in
// front of its occluder, uncertain behind; blocker also unlit behind its stopper; out unlit.
// BeamTree::leaf_region's twin, shared with the walk (walk.glsl).
int leaf_region(TreeNode leaf, vec3 q) {
    if (leaf.link.z == KIND_OPEN) return REGION_LIT;
    if (leaf.link.z == KIND_SOLID) {
        return tree_distance(leaf.plane, q) > 0.0 ? REGION_LIT : REGION_UNCERTAIN;
    }
    if (leaf.link.z == KIND_BLOCKER) {
        if (tree_distance(leaf.plane, q) > 0.0) return REGION_LIT;
        return tree_distance(tree_planes[leaf.link.w], q) > 0.0 ? REGION_UNCERTAIN : REGION_UNLIT;
    }
    return REGION_UNLIT;  // out: outside the influence pyramid
}

int classify_region(vec3 p) {
    vec3 q = p - frame.light_position.xyz;
    if (!(tree_distance(tree_planes[0], q) < 0.0) || !(tree_distance(tree_planes[1], q) < 0.0)) {
        return REGION_UNLIT;  // outside the near and far ranges
    }
    int index = 0;
    TreeNode node = tree_nodes[0];
    while (node.link.z == KIND_SPLIT) {
        index = tree_distance(node.plane, q) >= 0.0 ? node.link.x : node.link.y;
        node = tree_nodes[index];
    }
    return leaf_region(node, q);
}
