#include "analytic/beamtree_method.h"

#include "analytic/gpu_tree.h"
#include "analytic/region_lists.h"
#include "analytic/region_pass.h"
#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/regions.h"
#include "beamtree/shaders/classify_interface.h"
#include "frame/method_registry.h"
#include "gl/platform.h"

namespace sl::analytic {

namespace {

// The `surfaces` choices, in declaration order.
enum class Surfaces { boundary, cells, fragments };

class BeamTreeMethod final : public frame::VolumeMethod {
public:
    BeamTreeMethod() : VolumeMethod("beamtree") {
        surfaces_ = declare_choice(
            "surfaces", {"boundary", "cells", "fragments"}, Surfaces::boundary,
            "boundary: the lit union's boundary, each plane's faces merged into maximal polygons "
            "(docs/design.md §9); cells: every lit cell's faces (the first round's mesh); "
            "fragments: the boundary's faces fanned one by one (same integral in all three)");
        route_ = declare_choice("route", region_route_choices(), RegionRoute::automatic,
                                region_route_description());
        layout_ = declare_choice(
            "tree_layout", {"depth_first", "build"}, bt::GpuTreeLayout::depth_first,
            "walk route: the order of the tree's nodes on the GPU; depth_first: preorder, a "
            "descent's next node next in memory; build: as the tree grew (results/walk.md)");
        walk_stack_ = declare_integer(
            "walk_stack", SL_WALK_STACK_DEFAULT, 1, 256,
            "walk route: entries of the walk's short stack (beamtree/shaders/walk.glsl); a walk "
            "that drops entries restarts at the root from where it stands (results/walk.md)");
    }
    std::string accepts() const override { return AnalyticRegionPass::accepts(); }
    void prepare_light(const Scene& scene) override {
        software_ = gl::current_renderer_is_software();  // for route = auto
        built_ = false;
        update_light(scene, SceneChange::everything(scene));
    }
    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene& scene,
                                                       const SceneChange& change) const override {
        AnalyticRegionPass::require_closed_form(scene, name());
        if (walks(*route_, scene, software_)) {
            return region_frame_work(
                scene, change, {.gpu_tree = true, .layout = *layout_, .view_aspect = view_aspect()},
                built_, true);
        }
        const Surfaces surfaces = *surfaces_;
        return region_frame_work(
            scene, change,
            {.lit = true,
             .cells = surfaces == Surfaces::cells,
             .shape = surfaces == Surfaces::fragments ? bt::BoundaryShape::fragments
                                                      : bt::BoundaryShape::maximal,
             .view_aspect = view_aspect()},
            built_);
    }
    void apply_update_light(const Scene& scene, const SceneChange&,
                            std::unique_ptr<frame::FrameWork> work) override {
        if (auto* regions = dynamic_cast<RegionFrameWork*>(work.get())) {
            const bt::FrameRegions& r = regions->regions;
            stages_ = r.ms;
            pass_.upload_mesh(r.lit.positions, r.lit.triangles, scene.light, r.shared_sides);
            walk_ = regions->walk;
            if (walk_) {
                tree_.upload(r.gpu);
            }
            built_ = true;
        }
        pass_.set_scene(scene);
    }
    void render(const frame::VolumeInputs& inputs) override {
        if (walk_) {
            lists_.walk(inputs, tree_, false, 0, *walk_stack_);
            pass_.draw_walk(inputs, tree_);
        } else {
            pass_.draw(inputs);
        }
    }
    gl::TextureViews textures() const override { return pass_.textures(name()); }
    frame::MethodStatistics statistics() const override {
        frame::MethodStatistics stats = region_statistics(stages_, walk_);
        stats.push_back({"region_faces", double(pass_.triangle_count())});
        stats.push_back({"fragments_analytic", pass_.fragments()});
        stats.push_back({"fragments_rasterized", pass_.rasterized()});
        return stats;
    }

private:
    frame::Param<Surfaces> surfaces_;
    frame::Param<RegionRoute> route_;
    frame::Param<bt::GpuTreeLayout> layout_;
    frame::Param<int> walk_stack_;
    AnalyticRegionPass pass_;
    GpuTreeBuffers tree_;  // the walk route's tree
    RegionLists lists_;    // and the lit intervals it finds
    bt::RegionStageTimes stages_;
    bool built_ = false;
    bool walk_ = false;      // the last build was for the walk route
    bool software_ = false;  // the GL is a software rasterizer (prepare())
};

}  // namespace

void register_methods(frame::MethodRegistry& registry) {
    registry.add("beamtree", 10, [] { return std::make_unique<BeamTreeMethod>(); });
}

}  // namespace sl::analytic
