// The storage buffers of the beam tree on the GPU (classify.glsl, walk.glsl), shared by
// analytic/gpu_tree.cpp, which uploads them, and the shaders.
#ifndef SL_CLASSIFY_INTERFACE_H
#define SL_CLASSIFY_INTERFACE_H

#define SL_TREE_NODES_BINDING 1
#define SL_TREE_PLANES_BINDING 2
// Entries of walk.glsl's short stack unless a program defines SL_WALK_STACK (beamtree's
// walk_stack parameter; results/walk.md).
#define SL_WALK_STACK_DEFAULT 24

#endif
