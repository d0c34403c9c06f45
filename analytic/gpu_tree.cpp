#include "analytic/gpu_tree.h"

#include "beamtree/shaders/classify_interface.h"
#include "gl/functions.h"

namespace sl::analytic {

namespace {}  // namespace

void GpuTreeBuffers::upload(const bt::GpuTree& tree) {
    nodes_ = gl::create_buffer(tree.nodes.data(), tree.nodes.size() * sizeof(tree.nodes[0]));
    planes_ = gl::create_buffer(tree.planes.data(), tree.planes.size() * sizeof(tree.planes[0]));
}

void GpuTreeBuffers::bind() const {
    gl::GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_TREE_NODES_BINDING, nodes_.id());
    gl::GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, SL_TREE_PLANES_BINDING, planes_.id());
}

const std::vector<std::string>& region_route_choices() {
    static const std::vector<std::string> choices = {"auto", "walk", "mesh"};
    return choices;
}

const char* region_route_description() {
    return "walk: each eye ray walks the beam tree on the GPU, the CPU builds only the tree per "
           "change; mesh: the CPU builds the region pieces and boundary meshes, the GPU "
           "rasterizes them (same image, docs/design.md §14); auto: walk when the scene is "
           "animated and the GL is a GPU, mesh when it is still or the GL is a software "
           "rasterizer (llvmpipe)";
}

bool walks(RegionRoute route, const Scene& scene, bool software) {
    return route == RegionRoute::walk ||
           (route == RegionRoute::automatic && scene.animation && !software);
}

}  // namespace sl::analytic
