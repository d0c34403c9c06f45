#include "analytic/beamtree_method.h"

#include <chrono>

#include "analytic/region_pass.h"
#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"

namespace sl::analytic {

namespace {

class BeamTreeMethod final : public gl::VolumeMethod {
public:
    std::string name() const override { return "beamtree"; }
    void prepare(const Scene& scene) override {
        AnalyticRegionPass::require_closed_form(scene, name());
        const auto start = std::chrono::steady_clock::now();
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
        const bt::RegionMesh lit = bt::extract_regions(tree).mesh(bt::Region::lit);
        build_ms_ =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        pass_.upload(scene, lit.positions, lit.triangles);
    }
    void render(const gl::VolumeInputs& inputs) override { pass_.draw(inputs); }
    gl::TextureViews textures() const override { return pass_.textures(name()); }
    gl::MethodStatistics statistics() const override {
        return {{"cpu_ms_beamtree", build_ms_}, {"region_faces", double(pass_.triangle_count())}};
    }

private:
    AnalyticRegionPass pass_;
    double build_ms_ = 0.0;
};

}  // namespace

std::unique_ptr<gl::VolumeMethod> create_beamtree_method() {
    return std::make_unique<BeamTreeMethod>();
}

}  // namespace sl::analytic
