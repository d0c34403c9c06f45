#include "analytic/gpu_tree.h"

#include "gl/functions.h"

namespace sl::analytic {

namespace {
constexpr GLuint kTreeNodesBinding = 1, kTreePlanesBinding = 2;  // classify.glsl
}  // namespace

void GpuTreeBuffers::upload(const bt::GpuTree& tree) {
    nodes_ = gl::create_buffer(tree.nodes.data(), tree.nodes.size() * sizeof(tree.nodes[0]));
    planes_ = gl::create_buffer(tree.planes.data(), tree.planes.size() * sizeof(tree.planes[0]));
}

void GpuTreeBuffers::bind() const {
    gl::GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, kTreeNodesBinding, nodes_.id());
    gl::GL.BindBufferBase(GL_SHADER_STORAGE_BUFFER, kTreePlanesBinding, planes_.id());
}

frame::Parameter region_route_parameter() {
    return {.name = "route",
            .type = frame::Parameter::Type::choice,
            .default_value = 0,
            .description =
                "walk: each eye ray walks the beam tree on the GPU, the CPU builds "
                "only the tree per change; mesh: the CPU builds the region pieces "
                "and boundary meshes, the GPU rasterizes them (same image, "
                "docs/design.md §14); auto: walk when the scene is animated and the GL "
                "is a GPU, mesh when it is still or the GL is a software rasterizer "
                "(llvmpipe)",
            .choices = {"auto", "walk", "mesh"}};
}

bool walks(RegionRoute route, const Scene& scene, bool software) {
    return route == RegionRoute::walk ||
           (route == RegionRoute::automatic && scene.animation && !software);
}

}  // namespace sl::analytic
