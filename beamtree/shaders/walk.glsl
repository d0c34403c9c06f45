// The beam tree's trace() on the GPU (beamtree/beam_tree.h, docs/design.md §14): the regions
// along a segment, walked through the tree the CPU built this frame (BeamTree::gpu_tree()), so
// that no region pieces and no boundary meshes need building per frame. The includer defines
//     void walk_piece(int region, float begin, float end);
// and tree_walk() calls it for each piece of [t0, t1] in order of t: consecutive pieces tile the
// segment and differ in region (trace()'s intervals). Needs frame_uniforms.h and classify.glsl.
//
// The walk is classify()'s descent applied to a whole segment (Nilsson Program 2 on an interval):
// at a split node, the segment's part on each side of the plane (distances a + b t, linear in t,
// planes relative to the light so that float keeps the tree's ε) goes down that side, the nearer
// part first. The farther parts wait on a short stack (Horn, Sugerman, Houston & Hanrahan,
// "Interactive k-D tree GPU raytracing", I3D 2007): when it overflows the oldest entry is
// dropped, and when it runs dry before the segment's end the walk restarts at the root from
// where it stands. Deep trees (multiple:256 has depth > 100) cost a few restarts, never a wrong
// piece. A leaf's occluder and stopper cut its piece into at most three parts, each classified
// at its middle as classify() would (classify.glsl's leaf_region).
#ifndef SL_WALK_STACK
#define SL_WALK_STACK SL_WALK_STACK_DEFAULT
#endif
// Node visits before a walk gives up (a corrupt tree must not hang the GPU): the rest of the
// segment is reported as uncertain, which the hybrids march and beamtree leaves dark.
const int WALK_MAX_STEPS = 1 << 16;

void walk_piece(int region, float begin, float end);

// The run of pieces of one region the walk is in: consecutive pieces of a region are merged, so
// that walk_piece() is called once per change of region rather than once per leaf. Inside the
// walk's loop every lane of a SIMD group runs what any lane runs: the consumer's work (list
// writes, G) there cost half the walk on llvmpipe before the merge.
int walk_run_region = -1;
float walk_run_begin = 0.0, walk_run_end = 0.0;

void walk_emit(int region, float begin, float end) {
    if (!(end > begin))
        return;
    if (region == walk_run_region && begin == walk_run_end) {
        walk_run_end = end;
        return;
    }
    if (walk_run_region >= 0)
        walk_piece(walk_run_region, walk_run_begin, walk_run_end);
    walk_run_region = region;
    walk_run_begin = begin;
    walk_run_end = end;
}

void walk_finish() {
    if (walk_run_region >= 0)
        walk_piece(walk_run_region, walk_run_begin, walk_run_end);
    walk_run_region = -1;
}

// Where the plane's distance a + b t changes sign inside (begin, end), or -1.
float walk_cut(vec4 plane, vec3 q0, vec3 direction, float begin, float end) {
    float b = dot(plane.xyz, direction);
    if (b == 0.0)
        return -1.0;
    float t = -tree_distance(plane, q0) / b;
    return t > begin && t < end ? t : -1.0;
}

// The pieces of origin + t·direction, t in [t0, t1] (0 <= t0 < t1, both finite). False when the
// walk gave up after WALK_MAX_STEPS node visits.
bool tree_walk(vec3 origin, vec3 direction, float t0, float t1) {
    vec3 q0 = origin - frame.light_position.xyz;
    // Inside the near and far ranges (classify's test) and the influence pyramid (the tree's
    // root chain, nodes 0-3: their back sides): all six distances negative. Most eye rays miss
    // the pyramid and stop here; the rest start inside it.
    float inside0 = t0, inside1 = t1;
    for (int i = 0; i < 6; ++i) {
        vec4 plane = i < 2 ? tree_planes[i] : tree_nodes[i - 2].plane;
        float a = tree_distance(plane, q0), b = dot(plane.xyz, direction);
        if (b == 0.0) {
            if (!(a < 0.0))
                inside1 = inside0;
        } else if (b > 0.0) {
            inside1 = min(inside1, -a / b);
        } else {
            inside0 = max(inside0, -a / b);
        }
    }
    if (!(inside1 > inside0)) {
        walk_emit(REGION_UNLIT, t0, t1);
        walk_finish();
        return true;
    }
    walk_emit(REGION_UNLIT, t0, inside0);

    // One vec2 per entry (begin, end) and the node in an ivec: fewer indirect accesses, which
    // a software rasterizer pays per lane.
    vec2 stack_span[SL_WALK_STACK];
    int stack_node[SL_WALK_STACK];
    int top = 0, size = 0;  // a ring: the newest entry at top - 1, `size` entries kept
    // The segment lies inside the pyramid: below the root chain's four sides (restarts too);
    // a sun's window has its cuts there, the chain's rest (BeamTree::chain()).
    int root = tree_nodes[3].link.y;
    int index = root;
    float begin = inside0, end = inside1;
    bool finished = false;
    for (int step = 0; step < WALK_MAX_STEPS; ++step) {
        TreeNode node = tree_nodes[index];
        if (node.link.z == KIND_SPLIT) {
            float a = tree_distance(node.plane, q0), b = dot(node.plane.xyz, direction);
            bool front_begin = a + b * begin >= 0.0;
            bool front_end = a + b * end >= 0.0;
            if (front_begin == front_end) {
                index = front_begin ? node.link.x : node.link.y;
                continue;
            }
            float t = b != 0.0 ? clamp(-a / b, begin, end) : 0.5 * (begin + end);
            stack_node[top] = front_end ? node.link.x : node.link.y;
            stack_span[top] = vec2(t, end);
            top = top + 1 == SL_WALK_STACK ? 0 : top + 1;
            size = min(size + 1, SL_WALK_STACK);
            index = front_begin ? node.link.x : node.link.y;
            end = t;
            continue;
        }
        // A leaf: its occluder and stopper cut the piece into at most three parts.
        float cut0 = -1.0, cut1 = -1.0;
        if (node.link.z == KIND_SOLID || node.link.z == KIND_BLOCKER) {
            cut0 = walk_cut(node.plane, q0, direction, begin, end);
        }
        if (node.link.z == KIND_BLOCKER) {
            cut1 = walk_cut(tree_planes[node.link.w], q0, direction, begin, end);
        }
        // The parts' ends in order: begin, c1, c2, end (c1 = c2 = end without cuts).
        float c1 = end, c2 = end;
        if (cut0 >= 0.0 && cut1 >= 0.0) {
            c1 = min(cut0, cut1);
            c2 = max(cut0, cut1);
        } else if (cut0 >= 0.0 || cut1 >= 0.0) {
            c1 = max(cut0, cut1);
        }
        // One call site in the loop (the parts' count is not a constant, so it stays a loop).
        int parts = c2 < end ? 3 : c1 < end ? 2 : 1;
        for (int k = 0; k < parts; ++k) {
            float from = k == 0 ? begin : k == 1 ? c1 : c2;
            float to = k == 0 ? c1 : k == 1 ? c2 : end;
            float middle = 0.5 * (from + to);
            walk_emit(leaf_region(node, q0 + middle * direction), from, to);
        }
        if (size > 0) {
            top = top == 0 ? SL_WALK_STACK - 1 : top - 1;
            --size;
            index = stack_node[top];
            begin = stack_span[top].x;
            end = stack_span[top].y;
        } else if (end < inside1) {
            index = root;  // dropped entries: restart at the root from here
            begin = end;
            end = inside1;
        } else {
            finished = true;
            break;
        }
    }
    if (!finished)
        walk_emit(REGION_UNCERTAIN, begin, inside1);  // gave up
    walk_emit(REGION_UNLIT, inside1, t1);
    walk_finish();
    return finished;
}
