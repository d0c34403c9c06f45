// Scene files: the canonical scenes, the multiple:N generator, and every kind of bad input.

#include <fstream>
#include <variant>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <sstream>

#include "core/error.h"
#include "scenes/scene_file.h"
#include "tests/support.h"

namespace sl::test {
namespace {

namespace fs = std::filesystem;

// Every canonical scene loads, with a camera, a light, objects and real meshes.
TEST(SceneFile, CanonicalScenesLoad) {
    for (const std::string& name : canonical_scene_names()) {
        const Scene scene = load_canonical(name);
        EXPECT_EQ(scene.name, name);
        EXPECT_GE(scene.objects.size(), 5u) << name;
        EXPECT_GT(scene.triangle_count(), 1000u) << name;
        EXPECT_GT(scene.medium.sigma_s.x, 0.0f) << name;
    }
    const Scene toplight = load_canonical("toplight");
    bool has_bunny = false;
    for (const Object& object : toplight.objects) {
        has_bunny |= object.name == "bunny" && object.mesh->positions.size() == 37706;
    }
    EXPECT_TRUE(has_bunny);
    // Toplight: the light points down, orthogonal (within 15°) to the view direction.
    const glm::vec3 view = glm::normalize(toplight.camera.target - toplight.camera.position);
    EXPECT_LT(toplight.light.direction().y, -0.95f);
    EXPECT_LT(std::abs(glm::dot(view, toplight.light.direction())), std::sin(glm::radians(15.0f)));
    // Parallel: the light's axis is within 15° of the view direction.
    const Scene parallel = load_canonical("parallel");
    const glm::vec3 parallel_view =
        glm::normalize(parallel.camera.target - parallel.camera.position);
    EXPECT_GT(glm::dot(parallel_view, parallel.light.direction()), std::cos(glm::radians(15.0f)));
}

// The checked-in scenes/multiple.toml is exactly what the generator writes for the default N.
TEST(SceneFile, MultipleSceneFileIsTheGeneratorOutput) {
    std::ifstream in(fs::path(SHAFTLAB_SOURCE_DIR) / "scenes" / "multiple.toml");
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), generate_multiple_scene(kMultipleDefaultCount))
        << "regenerate it: build/shaftlab scenes --generate " << kMultipleDefaultCount
        << " > scenes/multiple.toml";
}

// multiple:N has N objects plus the floor, is deterministic in N, keeps every object under the
// light, and no two objects overlap.
TEST(SceneFile, MultipleNGeneratesNDisjointObjectsUnderTheLight) {
    for (const int n : {1, 7, 50, 400}) {
        const Scene scene = load_canonical("multiple:" + std::to_string(n));
        ASSERT_EQ(scene.objects.size(), size_t(n) + 1);
        EXPECT_EQ(generate_multiple_scene(n), generate_multiple_scene(n));
        std::vector<Bounds> boxes;
        for (size_t i = 1; i < scene.objects.size(); ++i) {
            Bounds b;
            for (const glm::vec3& p : scene.objects[i].mesh->positions) {
                b.extend(glm::vec3(scene.objects[i].transform * glm::vec4(p, 1.0f)));
            }
            EXPECT_GE(b.min.y, -1e-4f);
            const glm::vec3 top_center(b.center().x, b.max.y, b.center().z);
            EXPECT_GT(scene.light.cone_factor(top_center), 0.0f) << "object " << i;
            for (const Bounds& other : boxes) {
                const bool apart = b.max.x < other.min.x || other.max.x < b.min.x ||
                                   b.max.z < other.min.z || other.max.z < b.min.z;
                EXPECT_TRUE(apart) << "multiple:" << n << " object " << i << " overlaps";
            }
            boxes.push_back(b);
        }
    }
    EXPECT_THROW(load_canonical("multiple:0"), Error);
    EXPECT_THROW(load_canonical("multiple:abc"), Error);
}

constexpr const char* kMinimalScene = R"([camera]
position = [0.0, 1.0, 5.0]
target = [0.0, 0.0, 0.0]
fov = 45.0

[light]
position = [0.0, 5.0, 0.0]
target = [0.0, 0.0, 0.0]
cone_angle = 30.0

[[objects]]
shape = "box"
inner = [{ min = [-0.25, -0.25, -0.25], max = [0.25, 0.25, 0.25] }]
)";

constexpr const char* kLightBlock = R"([light]
position = [0.0, 5.0, 0.0]
target = [0.0, 0.0, 0.0]
cone_angle = 30.0
)";

constexpr const char* kSun = R"(
[[lights]]
type = "directional"
)";

constexpr const char* kPointLight = R"(
[[lights]]
type = "point"
position = [0.0, 2.0, 0.0]
near = 0.2
far = 8.0
intensity = [5.0, 5.0, 5.0]
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
}

// A minimal scene takes the documented defaults and its explicit inner box.
TEST(SceneFile, MinimalSceneTakesDefaults) {
    TempDir dir;
    write_text(dir / "minimal.toml", kMinimalScene);
    const Scene scene = load_scene((dir / "minimal.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(scene.name, "minimal");
    EXPECT_EQ(scene.medium.model, MediumModel::simplified);
    ASSERT_EQ(scene.objects.size(), 1u);
    ASSERT_EQ(scene.objects[0].inner_boxes.size(), 1u);
    EXPECT_EQ(scene.objects[0].inner_boxes[0].max, glm::vec3(0.25f));
    EXPECT_EQ(scene.materials[size_t(scene.objects[0].material)].name, "default");
}

struct BadInput {
    std::string text;      // the scene file
    std::string expected;  // in its error message
};

// Bad scene files and what their errors say. Longer than a screen because it is one table: a
// line per case, read down the column of messages.
std::vector<BadInput> bad_inputs() {
    const std::string s = kMinimalScene;
    return {
        {"[camera\n", "malformed TOML"},
        {s + "[extra]\nx = 1\n", "extra: unknown key"},
        {replace(s, "fov = 45.0", "fov = 45.0\nfocus = 3.0"), ":5: [camera] focus: unknown key"},
        {replace(s, "fov = 45.0", "fov = 0.0"), "[camera] fov: must be in (0, 180)"},
        {replace(s, "fov = 45.0", "fov = nan"), "[camera] fov: value nan is not finite"},
        {replace(s, "fov = 45.0", "fov = \"wide\""), "[camera] fov: expected a number"},
        {replace(s, "target = [0.0, 0.0, 0.0]\nfov", "target = [0.0, 1.0, 5.0]\nfov"),
         "camera target equals its position"},
        {replace(s, "position = [0.0, 1.0, 5.0]", "position = [0.0, 1.0]"),
         "[camera] position: expected an array of three numbers"},
        {replace(s, "position = [0.0, 1.0, 5.0]", "position = [0.0, inf, 5.0]"),
         "[camera] position: component 1 is not finite"},
        // Values that become float32 are checked as float32 (1e39 is infinite
        // there: a black image, a misleading error or a NaN later), with sane bounds.
        {replace(s, "position = [0.0, 1.0, 5.0]", "position = [1e39, 1.0, 5.0]"),
         ":2: [camera] position: component 0 is 1e+39: must be within ±1e+06"},
        {replace(s, "fov = 45.0", "fov = 45.0\nup = [0.0, 1e20, 0.0]"),
         "[camera] up: component 1 is 1e+20: must be within ±1e+06"},
        {replace(s, "fov = 45.0", "fov = 45.0\nup = [0.0, 0.0, 0.0]"),
         "[camera] up: up vector must not be [0, 0, 0]"},
        {replace(s, "fov = 45.0", "fov = 45.0\nup = [0.0, 1e-30, 5e-30]"),
         "[camera] up: up vector is parallel to the view direction"},
        // A black-box fuzz's find: a subnormal up aborted inside Embree (its rays were NaN).
        {replace(s, "fov = 45.0", "fov = 45.0\nup = [0.0, 1e-45, 0.0]"),
         ":5: [camera] up: component 1 is 1e-45: below float32's smallest normal number"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 1e-40"),
         "[light] cone_angle: value 1e-40 is below float32's smallest normal number"},
        {replace(s, "target = [0.0, 0.0, 0.0]\nfov", "target = [0.0, 1.0, 5.000001]\nfov"),
         "camera target equals its position (or is too near it"},
        {replace(s, "target = [0.0, 0.0, 0.0]\ncone_angle",
                 "target = [0.0, 5.000001, 0.0]\ncone_angle"),
         "[light] target: light target equals its position (or is too near it"},
        {replace(s, "shape = \"box\"", "shape = \"sphere\"\nsegments = 4096"),
         "segments: expected an integer in [4, 1024]"},
        {replace(s, "shape = \"box\"",
                 "shape = \"torus\"\nmajor_segments = 4096\nminor_segments = 4096"),
         "minor_segments: major_segments × minor_segments = 4096 × 4096 makes 33554432 "
         "triangles, at most 1048576"},
        {replace(s, "position = [0.0, 5.0, 0.0]", "position = [0.0, 1e39, 0.0]"),
         "[light] position: component 1 is 1e+39"},
        {replace(s, "target = [0.0, 0.0, 0.0]\ncone_angle",
                 "target = [0.0, 0.0, -1e39]\ncone_angle"),
         "[light] target: component 2 is -1e+39"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nintensity = [1e39, 1.0, 1.0]"),
         "[light] intensity: component 0 is 1e+39"},
        {s + "[medium]\nsigma_s = [0.1, 1e39, 0.1]\n", "[medium] sigma_s: component 1 is 1e+39"},
        {replace(s, "shape = \"box\"", "shape = \"box\"\ntranslate = [1e39, 0.0, 0.0]"),
         "translate: component 0 is 1e+39"},
        {replace(s, "shape = \"box\"", "shape = \"box\"\nrotate = [0.0, 1e39, 0.0]"),
         "rotate: component 1 is 1e+39"},
        {s + "[medium]\na0 = 1e39\n", "[medium] a0: must be in [0, "},
        // Pieces are cut from full hulls; with reduced hulls they were ignored without a word.
        {s + "[beamtree]\noccluders = \"mesh\"\n",
         "[beamtree] occluders: unknown value 'mesh' (volumes, triangles, auto)"},
        {s + "[beamtree]\nmax_triangles = -1\n", "[beamtree] max_triangles: "},
        {s + "[beamtree]\nmin_inner_fill = 1.5\n", "[beamtree] min_inner_fill: must be in [0, 1]"},
        {s + "[beamtree]\nmax_outer_planes = 24\npieces = true\n",
         "[beamtree] pieces: convex pieces need full hulls, but max_outer_planes = 24"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 95.0"), "[light] cone_angle: must be in"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nintensity = [1.0, -1.0, 1.0]"),
         "[light] intensity: components must not be negative"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nfalloff = 40.0"),
         "[light] falloff: must be in [0, 30]"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nnear = 5.0\nfar = 2.0"),
         "[light] far: must be in"},
        {s + "[medium]\nmodel = \"exact\"\n", "[medium] model: unknown value 'exact'"},
        {s + "[medium]\nphase = \"hg\"\n", "[medium] phase: unknown value 'hg'"},
        {s + "[medium]\na0 = 0.0\na1 = 0.0\n", "a0 and a1 must not both be zero"},
        {s + "[medium]\ng = 1.0\n", "[medium] g: must be in (-1, 1)"},
        {s + "[medium]\ng = 0.6\n", "[medium] g: g = 0.6 is ignored by phase 'isotropic'"},
        {s + "[medium]\nphase = \"rayleigh\"\ng = -0.3\n", "ignored by phase 'rayleigh'"},
        {replace(s, "fov = 45.0", "fov = 45.0\nfvo = 50.0"),
         "[camera] fvo: unknown key (did you mean 'fov'?) (known: "},
        {s + "[medium]\ng = -1.0\n", "[medium] g: must be in (-1, 1)"},
        {s + "[medium]\nsigma_s = [0.1, -0.1, 0.1]\n",
         "[medium] sigma_s: components must not be negative"},
        {s + "[medium]\nsigma_a = [-1.0, 0.0, 0.0]\n",
         "[medium] sigma_a: components must not be negative"},
        {replace(s, "shape = \"box\"", "shape = \"cone\""), "shape: unknown shape 'cone'"},
        {replace(s, "shape = \"box\"", "shape = \"box\"\nmaterial = \"gold\""),
         "material: unknown material 'gold'"},
        {replace(s, "shape = \"box\"", "shape = \"box\"\nsize = [1.0, 0.0, 1.0]"),
         "size: components must be positive"},
        {replace(s, "shape = \"box\"", "shape = \"box\"\nscale = 0.0"), "scale: must be finite"},
        {replace(s, "shape = \"box\"", "shape = \"mesh\"\nfile = \"nowhere.off\""),
         "file: mesh 'nowhere.off' not found"},
        {replace(s, "shape = \"box\"", "shape = \"sphere\"\nsegments = 2"),
         "segments: expected an integer in [4, 1024]"},
        {replace(s, "max = [0.25, 0.25, 0.25]", "max = [0.25, -0.5, 0.25]"),
         "inner[0] max: must exceed min"},
        {replace(s, "[[objects]]", "[objects]"), "objects: expected an array"},
        {"[light]\nposition = [0.0, 5.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n",
         "missing required table [camera]"},
        // The lights: [light] or [[lights]], each entry typed, each type's keys alone.
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nshape = \"cube\""),
         "[light] shape: unknown value 'cube'"},
        {replace(s, "cone_angle = 30.0", "cone_angle = 30.0\nshape = \"pyramid\"\nfalloff = 5.0"),
         "[light] falloff: a pyramid has a hard edge"},
        {s + kPointLight, "[light] and [[lights]] both given"},
        {replace(s, "[light]", "[[lights]]"), "[[lights]] #1 type: missing: expected \"spot\","},
        {replace(s, "[light]", "[[lights]]\ntype = \"sun\""),
         "[[lights]] #1 type: unknown light type 'sun'"},
        {replace(s, kLightBlock, "") + kSun + "direction = [0.0, 0.0, 0.0]\n",
         "[[lights]] #1 direction: the direction the light travels must not be [0, 0, 0]"},
        {replace(s, kLightBlock, "") + kSun +
             "direction = [0.0, -1.0, 0.0]\nirradiance = [1.0, "
             "-1.0, 1.0]\n",
         "[[lights]] #1 irradiance:"},
        {replace(s, kLightBlock, "") + kSun + "direction = [0.0, -1.0, 0.0]\ncone_angle = 30.0\n",
         "[[lights]] #1 cone_angle: unknown key"},
        {replace(s, kLightBlock, "") + kSun +
             "direction = [0.0, -1.0, 0.0]\nentry = [0.0, "
             "-50.0, 0.0]\n",
         "[[lights]] #1: key \"entry\": the entry plane lies beyond the whole scene"},
        {replace(s, kLightBlock, "") + kPointLight + "cone_angle = 30.0\n",
         "[[lights]] #1 cone_angle: unknown key"},
        {replace(s, kLightBlock, "") + kPointLight +
             "[[lights]]\ntype = \"point\"\nposition = [0.0, 1.0, 0.0]\nfar = -1.0\n",
         "[[lights]] #2 far: must be in"},
        {"lights = []\n" + replace(s, kLightBlock, ""), "[[lights]] is empty"},
        {replace(s, kLightBlock, ""), "missing the light: a [light] table"},
        {[&] {
             std::string many = replace(s, kLightBlock, "");
             for (int i = 0; i < 43; ++i)
                 many += kPointLight;
             return many;
         }(),
         "[[lights]]: 43 lights make 258 spot lights (a point light counts six faces); at most "
         "256"},
    };
}

// Each bad input gives one error line naming the file, the line, the table and the key, and why.
TEST(SceneFile, BadInputsGiveOneClearError) {
    TempDir dir;
    for (const BadInput& c : bad_inputs()) {
        const fs::path path = dir / "scene.toml";
        write_text(path, c.text);
        try {
            load_scene(path.string(), SceneSearchPaths::defaults());
            ADD_FAILURE() << "no error; expected '" << c.expected << "' for:\n" << c.text;
        } catch (const Error& e) {
            const std::string message = e.what();
            EXPECT_NE(message.find(c.expected), std::string::npos)
                << "expected '" << c.expected << "' in: " << message;
            EXPECT_NE(message.find("scene.toml"), std::string::npos) << message;
            EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
        }
    }
}

// Missing files and unknown names are errors, not crashes.
TEST(SceneFile, UnreadableFilesAndUnknownNamesAreErrors) {
    TempDir dir;
    EXPECT_THROW(load_scene((dir / "absent.toml").string(), SceneSearchPaths::defaults()), Error);
    EXPECT_THROW(load_scene("no-such-scene", SceneSearchPaths::defaults()), Error);
    fs::create_directory(dir / "directory.toml");
    EXPECT_THROW(load_scene((dir / "directory.toml").string(), SceneSearchPaths::defaults()),
                 Error);
}

// A derived scene ([scene] base) is its base with the derived keys on top: objects and meshes
// from the base, the derived camera, and keys it does not set kept from the base.
TEST(SceneFile, BaseSceneIsInheritedAndOverriddenKeyByKey) {
    TempDir dir;
    write_text(dir / "view.toml", R"([scene]
base = "toplight"
[camera]
position = [3.0, 2.0, 6.0]
[light]
cone_angle = 20.0
)");
    const Scene base = load_canonical("toplight");
    const Scene view = load_scene((dir / "view.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(view.name, "view");
    ASSERT_EQ(view.objects.size(), base.objects.size());
    EXPECT_EQ(view.triangle_count(), base.triangle_count());
    EXPECT_EQ(view.camera.position, glm::vec3(3.0f, 2.0f, 6.0f));
    EXPECT_EQ(view.camera.target, base.camera.target);
    EXPECT_EQ(view.light.cone_half_angle_degrees, 20.0f);
    EXPECT_EQ(view.light.position, base.light.position);
    EXPECT_EQ(view.medium.sigma_s, base.medium.sigma_s);

    // A base file relative to the derived one, chaining to a canonical scene.
    fs::create_directory(dir / "sub");
    write_text(dir / "sub" / "second.toml", "[scene]\nbase = \"../view.toml\"\nname = \"two\"\n");
    const Scene second =
        load_scene((dir / "sub" / "second.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(second.name, "two");
    EXPECT_EQ(second.camera.position, view.camera.position);

    // A cycle, an unknown base and a base of the wrong type are one clear error each.
    write_text(dir / "a.toml", "[scene]\nbase = \"b.toml\"\n");
    write_text(dir / "b.toml", "[scene]\nbase = \"a.toml\"\n");
    for (const auto& [file, expected] :
         {std::pair{"a.toml", "deeper than 8"}, std::pair{"bad.toml", "unknown scene"},
          std::pair{"type.toml", "expected the name"}}) {
        if (std::string(file) == "bad.toml")
            write_text(dir / file, "[scene]\nbase = \"nowhere\"\n");
        if (std::string(file) == "type.toml")
            write_text(dir / file, "[scene]\nbase = 3\n");
        try {
            load_scene((dir / file).string(), SceneSearchPaths::defaults());
            ADD_FAILURE() << file << " loaded";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    }
}

// scene_view_toml writes a file that reads back to exactly the scene's camera, light and medium,
// on top of the base's objects.
TEST(SceneFile, SavedViewReadsBackExactly) {
    Scene scene = load_canonical("parallel");
    scene.camera.position = {1.0f / 3.0f, 2.123456789f, -7.5e-3f};
    scene.camera.fov_y_degrees = 37.77f;
    scene.light.position += glm::vec3(0.1f, -0.2f, 0.3f);
    scene.light.cone_half_angle_degrees = 17.0f;
    scene.light.falloff_degrees = 2.5f;
    scene.medium.sigma_s = {0.1f, 0.2f, 1e-7f};
    scene.medium.phase = PhaseFunction::henyey_greenstein;
    scene.medium.g = -0.3f;
    TempDir dir;
    write_text(dir / "saved.toml", scene_view_toml(scene, "parallel", "saved view"));
    const Scene back = load_scene((dir / "saved.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(back.name, "saved view");
    EXPECT_EQ(back.camera.position, scene.camera.position);
    EXPECT_EQ(back.camera.fov_y_degrees, scene.camera.fov_y_degrees);
    EXPECT_EQ(back.light.position, scene.light.position);
    EXPECT_EQ(back.light.target, scene.light.target);
    EXPECT_EQ(back.light.falloff_degrees, scene.light.falloff_degrees);
    EXPECT_EQ(back.medium.sigma_s, scene.medium.sigma_s);
    EXPECT_EQ(back.medium.phase, scene.medium.phase);
    EXPECT_EQ(back.medium.g, scene.medium.g);
    EXPECT_EQ(back.triangle_count(), scene.triangle_count());
    EXPECT_FALSE(back.environment.enabled());
}

// Several lights ([[lights]]): spot and point lights as declared, the methods' spot lights with
// each point light as its six pyramids (+x, -x, +y, -y, +z, -z) after the spots, `light` the first
// of them; a derived scene's [[lights]] replaces its base's [light], and a saved view keeps them.
TEST(SceneFile, SeveralLightsReadAsDeclaredAndAsSpotLights) {
    TempDir dir;
    write_text(dir / "lamps.toml", R"([scene]
base = "parallel"
[[lights]]
type = "point"
position = [0.5, 2.0, -1.0]
near = 0.25
far = 9.0
intensity = [3.0, 4.0, 5.0]
[[lights]]
type = "spot"
position = [0.0, 5.0, 0.0]
target = [0.0, 0.0, 0.0]
cone_angle = 20.0
shape = "pyramid"
)");
    const Scene scene = load_scene((dir / "lamps.toml").string(), SceneSearchPaths::defaults());
    ASSERT_EQ(scene.lights.size(), 2u);
    ASSERT_TRUE(std::holds_alternative<PointLight>(scene.lights[0]));
    const PointLight& point = std::get<PointLight>(scene.lights[0]);
    EXPECT_EQ(point.far, 9.0f);
    const std::vector<SpotLight> spots = scene.spot_lights();
    ASSERT_EQ(spots.size(), 7u);
    EXPECT_EQ(scene.light, spots[0]);
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (size_t i = 0; i < 6; ++i) {
        EXPECT_EQ(spots[i].direction(), axes[i]) << i;  // exactly: the target moves one axis
        EXPECT_EQ(spots[i].shape, SpotShape::pyramid);
        EXPECT_EQ(spots[i].cone_half_angle_degrees, 45.0f);
        EXPECT_EQ(spots[i].near, 0.25f);
        EXPECT_EQ(spots[i].intensity, point.intensity);
        // Each face's frame is the cube's: its up vector lies along another axis.
        const glm::vec3 up = spots[i].up();
        EXPECT_EQ(glm::abs(up.x) + glm::abs(up.y) + glm::abs(up.z), 1.0f) << i;
    }
    EXPECT_EQ(spots[6].shape, SpotShape::pyramid);
    EXPECT_EQ(spots[6].cone_half_angle_degrees, 20.0f);
    const Scene view = scene.for_light(3);
    EXPECT_TRUE(view.lights.empty());
    EXPECT_EQ(view.light, spots[3]);
    EXPECT_EQ(view.objects.size(), scene.objects.size());

    // One spot light in [[lights]] is the scene's `light`, as [light] would be.
    Scene one = scene;
    one.set_lights({spots[6]});
    EXPECT_TRUE(one.lights.empty());
    EXPECT_EQ(one.light, spots[6]);

    // Saved and read back: the same lights.
    write_text(dir / "saved.toml", scene_view_toml(scene, "parallel", "saved"));
    const Scene back = load_scene((dir / "saved.toml").string(), SceneSearchPaths::defaults());
    EXPECT_EQ(back.lights, scene.lights);
    EXPECT_EQ(back.light, scene.light);

    // A derived scene's [light] replaces its base's [[lights]].
    write_text(dir / "one.toml",
               "[scene]\nbase = \"lamps.toml\"\n[light]\nposition = [0.0, "
               "4.0, 0.0]\ntarget = [0.0, 0.0, 0.0]\n");
    const Scene single = load_scene((dir / "one.toml").string(), SceneSearchPaths::defaults());
    EXPECT_TRUE(single.lights.empty());
    EXPECT_EQ(single.light.position, glm::vec3(0.0f, 4.0f, 0.0f));
}

// A directional light: its direction normalised, its region the box around the objects and the
// camera, its entry plane by default the one touching that box on the light's side; as the spot
// light the methods take, parallel beams whose box holds every object corner and whose range
// starts at the entry plane. A given entry plane is kept; a saved view keeps the light.
TEST(SceneFile, ADirectionalLightCoversTheSceneFromItsEntryPlane) {
    TempDir dir;
    write_text(dir / "sun.toml", R"([scene]
base = "parallel"
[[lights]]
type = "directional"
direction = [1.0, -2.0, 0.5]
irradiance = [3.0, 2.5, 2.0]
)");
    const Scene scene = load_scene((dir / "sun.toml").string(), SceneSearchPaths::defaults());
    ASSERT_EQ(scene.lights.size(), 1u);
    const auto& sun = std::get<DirectionalLight>(scene.lights[0]);
    EXPECT_NEAR(glm::length(sun.direction), 1.0f, 1e-6f);
    const SpotLight beam = sun.beam();
    EXPECT_TRUE(beam.parallel());
    EXPECT_EQ(scene.light, beam);
    EXPECT_EQ(beam.intensity, glm::vec3(3.0f, 2.5f, 2.0f));
    // Every object's vertices, the camera and the region's corners inside the box, the nearest
    // corner on its entry plane.
    const glm::dvec3 d = glm::normalize(glm::dvec3(beam.direction()));
    double nearest = 1e30;
    auto check_inside = [&](const glm::vec3& p) {
        EXPECT_GT(beam.cone_factor(glm::dvec3(p)), 0.0) << p.x << " " << p.y << " " << p.z;
        const double depth = glm::dot(glm::dvec3(p) - glm::dvec3(beam.position), d);
        EXPECT_LE(depth, double(beam.far));
        return depth;
    };
    check_inside(scene.camera.position);
    for (const Object& object : scene.objects) {
        for (const glm::vec3& v : object.mesh->positions) {
            check_inside(glm::vec3(object.transform * glm::vec4(v, 1.0f)));
        }
    }
    for (int i = 0; i < 8; ++i) {
        nearest =
            std::min(nearest, check_inside(glm::vec3(i & 1 ? sun.region.max.x : sun.region.min.x,
                                                     i & 2 ? sun.region.max.y : sun.region.min.y,
                                                     i & 4 ? sun.region.max.z : sun.region.min.z)));
    }
    EXPECT_NEAR(nearest, 0.0, 1e-4);
    const Scene view = scene.for_light(0);
    EXPECT_EQ(view.light, beam);

    // A given entry plane: the range starts there.
    write_text(dir / "entry.toml",
               "[scene]\nbase = \"sun.toml\"\n[[lights]]\ntype = \"directional\"\ndirection = "
               "[0.0, -1.0, 0.0]\nentry = [0.0, 1.5, 0.0]\n");
    const Scene entered = load_scene((dir / "entry.toml").string(), SceneSearchPaths::defaults());
    EXPECT_NEAR(entered.light.position.y, 1.5f, 1e-5f);
    EXPECT_EQ(entered.light.near, 0.0f);

    // Saved and read back: the same light.
    write_text(dir / "saved.toml", scene_view_toml(scene, "parallel", "saved"));
    const Scene back = load_scene((dir / "saved.toml").string(), SceneSearchPaths::defaults());
    ASSERT_EQ(back.lights.size(), 1u);
    const auto& read = std::get<DirectionalLight>(back.lights[0]);
    EXPECT_LT(glm::length(read.direction - sun.direction), 1e-6f);  // normalised again
    EXPECT_EQ(read.irradiance, sun.irradiance);
    EXPECT_EQ(read.entry, sun.entry);
    EXPECT_EQ(read.region, sun.region);
}

// A saved view keeps the environment as the viewer left it: a studio light with every setting
// read back exactly, or off on a base scene that had one.
TEST(SceneFile, SavedViewKeepsTheEnvironment) {
    Scene scene = load_canonical("ibl-spheres");
    ASSERT_TRUE(scene.environment.enabled());
    scene.environment.file = SceneSearchPaths::defaults().environments / "forest.exr";
    scene.environment.intensity = 0.37f;
    scene.environment.rotation_degrees = 12.5f;
    scene.environment.face_size = 128;
    scene.environment.prefilter.method = ibl::PrefilterMethod::cone;
    scene.environment.prefilter.samples = 77;
    scene.environment.shading = ibl::Shading::moschos;
    scene.environment.skybox = false;
    TempDir dir;
    write_text(dir / "saved.toml", scene_view_toml(scene, "ibl-spheres", "saved"));
    const Environment back =
        load_scene((dir / "saved.toml").string(), SceneSearchPaths::defaults()).environment;
    EXPECT_EQ(back.file, scene.environment.file);
    EXPECT_EQ(back.intensity, 0.37f);
    EXPECT_EQ(back.rotation_degrees, 12.5f);
    EXPECT_EQ(back.face_size, 128);
    EXPECT_EQ(back.prefilter.describe(), scene.environment.prefilter.describe());
    EXPECT_EQ(back.shading, ibl::Shading::moschos);
    EXPECT_FALSE(back.skybox);

    scene.environment = Environment{};
    write_text(dir / "off.toml", scene_view_toml(scene, "ibl-spheres", "off"));
    EXPECT_FALSE(load_scene((dir / "off.toml").string(), SceneSearchPaths::defaults())
                     .environment.enabled());
}

}  // namespace
}  // namespace sl::test
