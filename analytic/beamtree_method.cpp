#include "analytic/beamtree_method.h"

#include <chrono>

#include "analytic/region_pass.h"
#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/regions.h"

namespace sl::analytic {

namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

class BeamTreeMethod final : public gl::VolumeMethod {
public:
    BeamTreeMethod() {
        declare({.name = "surfaces",
                 .type = gl::Parameter::Type::choice,
                 .default_value = 0,
                 .description = "boundary: the lit union's boundary (DESIGN.md §9); cells: every "
                                "lit cell's faces (the first round's mesh, same integral)",
                 .choices = {"boundary", "cells"}});
    }
    std::string name() const override { return "beamtree"; }
    std::string accepts() const override { return AnalyticRegionPass::accepts(); }
    void prepare(const Scene& scene) override {
        AnalyticRegionPass::require_closed_form(scene, name());
        auto start = std::chrono::steady_clock::now();
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
        const bt::Regions regions = bt::extract_regions(tree);
        build_ms_ = ms_since(start);
        start = std::chrono::steady_clock::now();
        const bt::RegionMesh lit = parameter("surfaces") == 0
                                       ? bt::boundary_mesh(tree, regions, bt::Region::lit)
                                       : regions.mesh(bt::Region::lit);
        mesh_ms_ = ms_since(start);
        pass_.upload(scene, lit.positions, lit.triangles);
    }
    void render(const gl::VolumeInputs& inputs) override { pass_.draw(inputs); }
    gl::TextureViews textures() const override { return pass_.textures(name()); }
    gl::MethodStatistics statistics() const override {
        return {{"cpu_ms_beamtree", build_ms_},
                {"cpu_ms_region_mesh", mesh_ms_},
                {"region_faces", double(pass_.triangle_count())},
                {"fragments_analytic", pass_.fragments()}};
    }

private:
    AnalyticRegionPass pass_;
    double build_ms_ = 0.0, mesh_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<gl::VolumeMethod> create_beamtree_method() {
    return std::make_unique<BeamTreeMethod>();
}

}  // namespace sl::analytic
