// The per-frame region work (beamtree/frame_regions.h) and its static half, the volume cache
// (beamtree/bounding_volumes.h): a frame of an animation built through the cached path equals a
// fresh build of the still scene at that time, PLY for PLY; the disk cache gives back exactly
// what was computed.

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "beamtree/boundary.h"
#include "beamtree/frame_regions.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl::bt {
namespace {

using test::TempDir;

std::string file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::string ply_bytes(const Regions& regions, const TempDir& dir, const std::string& name) {
    write_regions_ply(regions, dir / name);
    return file_bytes(dir / name);
}

bool same_mesh(const RegionMesh& a, const RegionMesh& b) {
    return a.positions == b.positions && a.triangles == b.triangles && a.beams == b.beams;
}

// SHAFTLAB_CACHE pointed at a fresh folder for one test.
class ScopedCache {
public:
    ScopedCache() {
        const char* old = std::getenv("SHAFTLAB_CACHE");
        old_ = old ? old : "";
        had_ = old != nullptr;
        setenv("SHAFTLAB_CACHE", dir_.path().c_str(), 1);
    }
    ~ScopedCache() {
        if (had_) {
            setenv("SHAFTLAB_CACHE", old_.c_str(), 1);
        } else {
            unsetenv("SHAFTLAB_CACHE");
        }
    }
    const TempDir& dir() const { return dir_; }

private:
    TempDir dir_;
    std::string old_;
    bool had_ = false;
};

// Every frame of each canonical animation: the per-frame path (the shared library's cached
// volumes transformed) against a fresh build of the still scene at that time, by a library that
// computes every volume itself. Regions PLY for PLY at every frame, and the walk route's update
// (the tree alone, analytic/gpu_tree.h) as the GPU reads it, bit for bit; the mesh route's
// boundary meshes and GPU tree at every 20th frame and the last (they cost most).
TEST(MovingRegions, PerFrameUpdateEqualsAFreshBuildAtEveryFrame) {
    TempDir dir;
    for (const std::string& name : animated_scene_names()) {
        const Scene scene = load_scene(name, SceneSearchPaths::defaults());
        const Animation& a = *scene.animation;
        VolumeLibrary fresh({.max_outer_planes = scene.bounds.max_outer_planes,
                             .automatic_inner = scene.bounds.automatic_inner});
        fresh.set_caching(false);
        for (int k = 0; k < a.frame_count(); ++k) {
            const bool meshes = k % 20 == 0 || k == a.frame_count() - 1;
            const Scene still = scene_at(scene, a.frame_time(k));
            const FrameRegions frame = build_frame_regions(
                still, {.lit = meshes, .uncertain = meshes, .gpu_tree = meshes, .pieces = true});
            const BeamTree tree(still.light, fresh.build(still, nullptr));
            const Regions regions = extract_regions(tree);
            const std::string label = fmt::format("{} frame {}", name, k);
            ASSERT_EQ(ply_bytes(*frame.regions, dir, "frame.ply"),
                      ply_bytes(regions, dir, "fresh.ply"))
                << label;
            const GpuTree gpu = tree.gpu_tree();
            const FrameRegions walk = build_frame_regions(still, {.gpu_tree = true});
            ASSERT_EQ(walk.gpu.nodes.size(), gpu.nodes.size()) << label;
            ASSERT_EQ(walk.gpu.planes.size(), gpu.planes.size()) << label;
            EXPECT_EQ(0, std::memcmp(walk.gpu.nodes.data(), gpu.nodes.data(),
                                     gpu.nodes.size() * sizeof(gpu.nodes[0])))
                << label;
            EXPECT_EQ(0, std::memcmp(walk.gpu.planes.data(), gpu.planes.data(),
                                     gpu.planes.size() * sizeof(gpu.planes[0])))
                << label;
            EXPECT_EQ(walk.ms.regions + walk.ms.lit + walk.ms.uncertain, 0.0)
                << label << ": the walk route builds no regions or meshes";
            if (!meshes) {
                continue;
            }
            EXPECT_TRUE(same_mesh(frame.lit, boundary_mesh(tree, regions, Region::lit))) << label;
            EXPECT_TRUE(same_mesh(frame.uncertain, boundary_mesh(tree, regions, Region::uncertain)))
                << label;
            ASSERT_EQ(frame.gpu.nodes.size(), gpu.nodes.size()) << label;
            EXPECT_EQ(0, std::memcmp(frame.gpu.nodes.data(), gpu.nodes.data(),
                                     gpu.nodes.size() * sizeof(gpu.nodes[0])))
                << label;
            EXPECT_GT(frame.ms.total(), 0.0);
        }
        EXPECT_EQ(fresh.stats().memory + fresh.stats().disk, 0u) << "the oracle shares nothing";
    }
}

// The objects of multiple-moving pass through each other's outer volumes: the tree must stay
// sound (classify agrees with its own trace) on the frame where they overlap most.
TEST(MovingRegions, OverlappingMovingObjectsKeepTheTreeConsistent) {
    const Scene scene = load_scene("multiple-moving", SceneSearchPaths::defaults());
    const Scene still = scene_at(scene, 2.0);  // the swapping pairs are half way
    const FrameRegions frame = build_frame_regions(still, {.pieces = true});
    const Regions& regions = *frame.regions;
    const double total = regions.volume[0] + regions.volume[1] + regions.volume[2];
    EXPECT_NEAR(total, regions.influence_volume, 1e-6 * regions.influence_volume)
        << "the regions tile the influence volume";
    EXPECT_GT(regions.volume[size_t(Region::uncertain)], 0.0);
}

TEST(VolumeCache, DiskRoundTripIsBitExactAndSkipsTheComputation) {
    const ScopedCache cache;
    const Scene scene = load_scene("toplight", SceneSearchPaths::defaults());
    const BoundsSettings options{.max_outer_planes = scene.bounds.max_outer_planes,
                                 .automatic_inner = scene.bounds.automatic_inner};
    VolumeLibrary::forget_process_volumes();
    VolumeLibrary first(options);
    const std::vector<ObjectVolumes> computed = first.build(scene, nullptr);
    EXPECT_EQ(first.stats().computed, scene.objects.size());
    EXPECT_EQ(first.stats().disk, 0u);

    VolumeLibrary::forget_process_volumes();  // as a new process would start
    VolumeLibrary second(options);
    const std::vector<ObjectVolumes> read = second.build(scene, nullptr);
    EXPECT_EQ(second.stats().disk, scene.objects.size()) << "every mesh read from the disk";
    EXPECT_EQ(second.stats().computed, 0u);
    ASSERT_EQ(read.size(), computed.size());
    for (size_t i = 0; i < read.size(); ++i) {
        const ConvexVolume& a = computed[i].outer;
        const ConvexVolume& b = read[i].outer;
        ASSERT_EQ(a.faces.size(), b.faces.size());
        for (size_t f = 0; f < a.faces.size(); ++f) {
            EXPECT_EQ(a.faces[f].vertices, b.faces[f].vertices);
            EXPECT_EQ(a.planes[f].normal, b.planes[f].normal);
            EXPECT_EQ(a.planes[f].offset, b.planes[f].offset);
        }
        EXPECT_EQ(computed[i].inner.size(), read[i].inner.size());
    }
    // In the same process, another library shares them from memory.
    VolumeLibrary third(options);
    third.build(scene, nullptr);
    EXPECT_EQ(third.stats().memory, scene.objects.size());

    // A corrupt file is computed again, never trusted.
    for (const auto& entry : std::filesystem::directory_iterator(cache.dir().path() / "volumes")) {
        if (entry.path().extension() == ".bin") {
            std::filesystem::resize_file(entry.path(), 40);
        }
    }
    VolumeLibrary::forget_process_volumes();
    VolumeLibrary fourth(options);
    const std::vector<ObjectVolumes> again = fourth.build(scene, nullptr);
    EXPECT_EQ(fourth.stats().computed, scene.objects.size());
    EXPECT_EQ(again[1].outer.faces.size(), computed[1].outer.faces.size());
    // Other settings are other keys.
    EXPECT_NE(volumes_key(*scene.objects[1].mesh, options),
              volumes_key(*scene.objects[1].mesh, {.max_outer_planes = 0}));
}

TEST(VolumeCache, AnInnerBoxOutsideItsMeshIsStillRefusedWhenCached) {
    const ScopedCache cache;
    Scene scene = load_scene("toplight", SceneSearchPaths::defaults());
    VolumeLibrary library;
    library.build(scene, nullptr);  // the box's explicit inner box verified and cached
    scene.objects[2].inner_boxes[0].max.x = 5.0f;
    VolumeLibrary::forget_process_volumes();
    VolumeLibrary other;
    EXPECT_THROW(other.build(scene, nullptr), Error);
}

}  // namespace
}  // namespace sl::bt
