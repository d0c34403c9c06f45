// The regions picture (beamtree/region_picture.h): what it must show under each kind of light.

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "beamtree/beam_tree.h"
#include "beamtree/bounding_volumes.h"
#include "beamtree/region_picture.h"
#include "scenes/scene_file.h"

namespace sl {
namespace {

// A camera under a roof, in its shadow, looking out past its edge into the sun: 4 m of unlit air,
// then lit air.
Scene under_a_roof(const std::string& light) {
    return parse_scene(R"([camera]
position = [-4.0, 1.5, 0.0]
target = [4.0, 1.5, 0.0]
fov = 30.0
)" + light + R"(
[[objects]]
name = "floor"
shape = "plane"
size = [12.0, 0.0, 12.0]
[[objects]]
name = "roof"
shape = "box"
size = [6.0, 0.2, 12.0]
translate = [-3.0, 3.0, 0.0]
)",
                       "roof.toml", {}, SceneSearchPaths::defaults());
}

// The picture's centre pixel over a black scene whose eye rays reach the far plane.
std::array<int, 3> centre_of_picture(const Scene& scene) {
    bt::VolumeLibrary library(scene.bounds);
    library.set_caching(false);
    const bt::BeamTree tree(scene.light, library.build(scene, nullptr));
    const int width = 64, height = 36;
    const std::vector<float> depth(size_t(width) * height, 1.0f);
    const std::vector<uint8_t> black(size_t(width) * height * 3, 0);
    const std::vector<uint8_t> picture = bt::draw_regions(scene, tree, depth, black, width, height);
    const size_t centre = (size_t(height / 2) * width + width / 2) * 3;
    return {picture[centre], picture[centre + 1], picture[centre + 2]};
}

// Under a sun, a camera inside a shadow (a room lit through its windows) sees the lit air behind
// metres of unlit air: the shafts show yellow through the shadow rather than being hidden by it,
// whatever the depth of the sun's box.
TEST(RegionPicture, ASunsShaftsShowThroughTheShadowTheCameraStandsIn) {
    const Scene scene = under_a_roof(R"([[lights]]
type = "directional"
direction = [0.0, -1.0, 0.0]
irradiance = [1.0, 1.0, 1.0]
)");
    ASSERT_TRUE(scene.light.parallel());
    const std::array<int, 3> rgb = centre_of_picture(scene);
    EXPECT_GT(rgb[0], 20) << "lit yellow behind the shadow: " << rgb[0] << " " << rgb[1] << " "
                          << rgb[2];
    EXPECT_GT(rgb[0], 3 * rgb[2]) << "yellow, not grey";
}

}  // namespace
}  // namespace sl
