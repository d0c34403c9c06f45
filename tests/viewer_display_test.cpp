// `shaftlab view` end to end, under a virtual X server (ctest runs this binary through xvfb-run):
// scripted runs of the three canonical scenes with the region overlay, checked against the beam
// tree's own classification of each pixel's eye ray; a saved experiment that the harness runs to
// the same image; the panels, previewer and error view drawn without a GL error.

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <cmath>
#include <fstream>

#include <fmt/format.h>
#include <glm/geometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/frame_regions.h"
#include "core/image.h"
#include "core/metrics.h"
#include "reference/reference.h"
#include "scenes/scene_file.h"
#include "tests/gl_support.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;

struct Png {
    int width = 0, height = 0;
    std::vector<unsigned char> rgb;
    glm::vec3 at(int x, int y) const {
        const size_t i = (size_t(y) * width + x) * 3;
        return {rgb[i], rgb[i + 1], rgb[i + 2]};
    }
};

Png read_png(const fs::path& path) {
    Png png;
    int channels = 0;
    unsigned char* data = stbi_load(path.c_str(), &png.width, &png.height, &channels, 3);
    if (!data) {
        ADD_FAILURE() << "cannot read " << path;
        return png;
    }
    png.rgb.assign(data, data + size_t(png.width) * png.height * 3);
    stbi_image_free(data);
    return png;
}

// Lengths of a pixel's eye ray (to its first hit) in the lit, uncertain and unlit regions.
std::array<double, 3> region_lengths(const Scene& scene, const bt::BeamTree& tree,
                                     const reference::ReferenceRenderer& embree,
                                     const PixelUnprojector& pixels, int x, int y) {
    const glm::dvec3 origin = pixels.point(x, y, -1.0);
    const glm::dvec3 direction = glm::normalize(pixels.point(x, y, 1.0) - origin);
    const double hit = embree.first_hit({origin, direction}, 100.0);
    std::array<double, 3> lengths{};
    constexpr int kSamples = 300;
    for (int s = 0; s < kSamples; ++s) {
        const glm::dvec3 p = origin + hit * (s + 0.5) / kSamples * direction;
        if (scene.light.in_influence_volume(glm::vec3(p))) {
            lengths[size_t(tree.classify(p))] += hit / kSamples;
        }
    }
    return lengths;
}

float yellowness(glm::vec3 c) {
    return 0.5f * (c.r + c.g) - c.b;
}
float luminance(glm::vec3 c) {
    return (c.r + c.g + c.b) / 3.0f;
}

// For each canonical scene, the overlay is where the regions project and nowhere else: pixels
// whose eye ray misses the influence volume are untouched, pixels looking through mostly lit
// air turn yellow, pixels looking through mostly unlit air turn darker; nothing is blank.
TEST(ViewerScripted, RegionOverlayAppearsWhereTheRegionsProject) {
    constexpr int kWidth = 160, kHeight = 100;
    TempDir dir;
    for (const std::string& name : canonical_scene_names()) {
        SCOPED_TRACE(name);
        const std::string common = fmt::format(
            "view --scene {} --method none --size {}x{} --frames 2 --no-ui --screenshot ", name,
            kWidth, kHeight);
        const CommandResult with =
            run_shaftlab(common + (dir / (name + "-overlay.png")).string() + " --layers volumes");
        ASSERT_EQ(with.exit_code, 0) << with.output;
        const CommandResult without = run_shaftlab(common + (dir / (name + "-plain.png")).string());
        ASSERT_EQ(without.exit_code, 0) << without.output;
        const Png overlay = read_png(dir / (name + "-overlay.png"));
        const Png plain = read_png(dir / (name + "-plain.png"));
        ASSERT_EQ(overlay.width, kWidth);
        ASSERT_EQ(overlay.height, kHeight);

        const Scene scene = load_canonical(name);
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene);
        const reference::ReferenceRenderer embree(scene);
        const PixelUnprojector pixels(scene.camera, kWidth, kHeight);
        double outside_diff = 0.0, lit_shift = 0.0, unlit_shift = 0.0, sum = 0.0, sum2 = 0.0;
        int outside = 0, lit = 0, unlit = 0;
        for (int y = 1; y < kHeight; y += 2) {
            for (int x = 1; x < kWidth; x += 2) {
                const std::array<double, 3> l = region_lengths(scene, tree, embree, pixels, x, y);
                const double total = l[0] + l[1] + l[2];
                const glm::vec3 a = overlay.at(x, y), b = plain.at(x, y);
                sum += luminance(a);
                sum2 += luminance(a) * luminance(a);
                if (total == 0.0) {
                    // Rays that graze the influence volume between CPU samples may still touch
                    // it on the GPU: count the pixels that changed, not the largest change.
                    outside_diff += glm::length(a - b) > 2.0f ? 1.0 : 0.0;
                    ++outside;
                } else if (l[0] > 0.9 * total && l[0] > 0.2 * scene.light.far) {
                    lit_shift += yellowness(a) - yellowness(b);
                    ++lit;
                } else if (l[2] > 0.6 * total && l[2] > 0.1 * scene.light.far) {
                    unlit_shift += luminance(a) - luminance(b);
                    ++unlit;
                }
            }
        }
        const int n = (kWidth / 2) * (kHeight / 2);
        const double stddev = std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
        EXPECT_GT(stddev, 10.0) << "not blank";
        ASSERT_GT(lit, 20) << "enough pixels see mostly lit air";
        EXPECT_GT(lit_shift / lit, 12.0) << "lit air turns yellow";
        if (outside > 0) {
            EXPECT_LE(outside_diff / outside, 0.04) << "no overlay where no region projects";
        }
        if (unlit > 10) {
            EXPECT_LT(unlit_shift / unlit, -3.0) << "unlit air turns darker";
        }
        std::printf("%s: %d outside (%.1f%% changed), %d lit (yellow +%.1f), %d unlit (%.1f)\n",
                    name.c_str(), outside, 100.0 * outside_diff / std::max(outside, 1), lit,
                    lit_shift / std::max(lit, 1), unlit, unlit_shift / std::max(unlit, 1));
    }
}

// In a scene of several lights the overlays show the regions of the spot light or point-light face
// that --light names (as `shaftlab regions --light N`): the viewer's tree for room's bulb's +x and
// -y faces is that face's own (its beam count), the two overlays differ, and a face the scene does
// not have is refused by name.
TEST(ViewerScripted, TheOverlaysShowTheChosenLightsRegions) {
    TempDir dir;
    const Scene scene = load_canonical("room");
    ASSERT_EQ(scene.spot_lights().size(), 6u);
    std::vector<Png> shots;
    for (const int light : {0, 3}) {
        const fs::path shot = dir / fmt::format("room-light{}.png", light);
        const CommandResult run = run_shaftlab(fmt::format(
            "view --scene room --method none --size 160x100 --frames 1 --no-ui --layers volumes "
            "--light {} --screenshot {}",
            light, shot.string()));
        ASSERT_EQ(run.exit_code, 0) << run.output;
        const bt::FrameRegions own =
            bt::build_frame_regions(scene.for_light(size_t(light)), {.pieces = true});
        EXPECT_NE(run.output.find(fmt::format("beam tree {} beams", own.regions->beam_count)),
                  std::string::npos)
            << "light " << light << ": " << run.output;
        shots.push_back(read_png(shot));
    }
    ASSERT_EQ(shots[0].rgb.size(), shots[1].rgb.size());
    size_t differ = 0;
    for (size_t i = 0; i < shots[0].rgb.size(); i += 3) {
        differ += shots[0].rgb[i] != shots[1].rgb[i] ? 1 : 0;
    }
    EXPECT_GT(differ, shots[0].rgb.size() / 3 / 20) << "the two faces' overlays differ";
    const CommandResult bad = run_shaftlab("view --scene room --light 6 --frames 1 --no-ui");
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_NE(bad.output.find("--light 6"), std::string::npos) << bad.output;
}

// A view reached by a camera and light path, saved as an experiment, is the view the harness
// renders: the bench's I_s for the saved cell equals the viewer's last frame.
TEST(ViewerScripted, SavedExperimentReproducesTheView) {
    TempDir dir;
    // The scene files' [animation] format (scenes/animation.h); at 1 fps frame k is time k.
    write_text(dir / "path.toml", R"([animation]
fps = 1
[[animation.camera]]
time = 0
position = [0.0, 2.4, 9.0]
[[animation.camera]]
time = 2
position = [3.0, 3.0, 8.0]
[[animation.light]]
time = 0
position = [1.2, 7.0, -0.8]
[[animation.light]]
time = 2
position = [0.5, 6.5, 0.2]
cone_angle = 26.0
)");
    const CommandResult viewed = run_shaftlab(fmt::format(
        "view --scene toplight --method march --set samples=24 --set clip=pyramid --size 96x64 "
        "--frames 3 --layers volumes,outlines,light-view,timings,previewer --path {} "
        "--in-scattering {} --save-experiment {} --screenshot {}",
        (dir / "path.toml").string(), (dir / "viewer.exr").string(),
        (dir / "saved" / "view.toml").string(), (dir / "ui.png").string()));
    ASSERT_EQ(viewed.exit_code, 0) << viewed.output;
    ASSERT_TRUE(fs::is_regular_file(dir / "saved" / "view.scene.toml"));
    // The light changed on every frame (its cone is held at the one key's 26 degrees from frame
    // 0 on): each change measured to the end of the frame that shows it.
    EXPECT_NE(viewed.output.find("3 scene changes; from a change to the end of the first frame"),
              std::string::npos)
        << viewed.output;

    const Scene saved =
        load_scene((dir / "saved" / "view.scene.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(saved.camera.position, glm::vec3(3.0f, 3.0f, 8.0f)) << "the path's last frame";
    EXPECT_EQ(saved.light.position, glm::vec3(0.5f, 6.5f, 0.2f));
    EXPECT_EQ(saved.light.cone_half_angle_degrees, 26.0f);

    const CommandResult bench =
        run_shaftlab(fmt::format("bench {} --out {} --set 'reference.method=\"\"'",
                                 (dir / "saved" / "view.toml").string(), (dir / "bench").string()));
    ASSERT_EQ(bench.exit_code, 0) << bench.output;
    fs::path exr;
    for (const auto& entry : fs::directory_iterator(dir / "bench" / "images")) {
        if (entry.path().extension() == ".exr")
            exr = entry.path();
    }
    ASSERT_FALSE(exr.empty()) << bench.output;
    EXPECT_NE(exr.filename().string().find("samples=24"), std::string::npos) << exr;
    const Image viewer_image = read_exr(dir / "viewer.exr");
    const Image bench_image = read_exr(exr);
    const ErrorMetrics difference = compare_images(bench_image, viewer_image);
    EXPECT_LT(difference.rel_rmse, 1e-4) << "the harness renders the viewer's view";
    double energy = 0.0;
    for (const float v : viewer_image.rgb)
        energy += v;
    EXPECT_GT(energy, 1.0) << "the view sees the shaft";

    const Png ui = read_png(dir / "ui.png");
    EXPECT_EQ(ui.width, 96);
}

// The panels, the buffer previewer on a method's own texture and the error view against a
// cached reference draw without a GL error; the error printed is the harness's metric.
TEST(ViewerScripted, PanelsPreviewerAndErrorView) {
    TempDir dir;
    const std::string cache = "SHAFTLAB_CACHE=" + (dir / "cache").string() + " ";
    const CommandResult reference = run_shaftlab_with(
        cache, fmt::format("render --scene toplight --method march --size 96x64 --compare "
                           "reference --out {}",
                           (dir / "render").string()));
    ASSERT_EQ(reference.exit_code, 0) << reference.output;
    const CommandResult viewed = run_shaftlab_with(
        cache, fmt::format("view --scene toplight --method march --size 96x64 --frames 2 "
                           "--layers error,previewer,timings,light-view --preview "
                           "'march/marching buffer (rgb I_s, a samples)' --screenshot {}",
                           (dir / "error.png").string()));
    ASSERT_EQ(viewed.exit_code, 0) << viewed.output;
    const size_t at = viewed.output.find("rel_rmse ");
    ASSERT_NE(at, std::string::npos) << viewed.output;
    const double rel_rmse = std::stod(viewed.output.substr(at + 9));
    EXPECT_LT(rel_rmse, 0.01) << viewed.output;
    const size_t rendered_at = reference.output.find("rel_rmse ");
    ASSERT_NE(rendered_at, std::string::npos) << reference.output;
    const double rendered = std::stod(reference.output.substr(rendered_at + 9));
    EXPECT_NEAR(rel_rmse, rendered, 0.01 * rendered + 1e-6)
        << "viewer and render agree on the error\n"
        << reference.output << viewed.output;

    const CommandResult wide = run_shaftlab(fmt::format(
        "view --scene multiple --method hybrid3 --size 640x400 --frames 2 --layers "
        "volumes,outlines,light-view,timings,previewer --preview 'hybrid3/interval uncertain "
        "exit' --screenshot {}",
        (dir / "panels.png").string()));
    ASSERT_EQ(wide.exit_code, 0) << wide.output;
    const Png panels = read_png(dir / "panels.png");
    ASSERT_EQ(panels.width, 640);
}

}  // namespace
}  // namespace sl::test
