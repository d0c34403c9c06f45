#pragma once
// Scene files (TOML); docs/scenes.md is the full reference. Every key is read in one of the
// scene_*.cpp files, next to its documentation and its validation; an unknown key, a wrong type
// or an out-of-range value is an error naming the file, line, table and key. The format:
//
//   [scene]     name, ambient = [r, g, b], base = "toplight" (optional: start from that scene, a
//               canonical name, multiple:N or a file relative to this one, and let this file's
//               tables override it key by key; [[objects]] replace the base's objects)
//   [camera]    position, target, up, fov (vertical, degrees), near, far, exposure
//   [light]     position, target, cone_angle (half-angle, degrees), near, far,
//               intensity = [r, g, b], falloff (degrees, 0 = hard edge)
//   [medium]    sigma_s, sigma_a ([r, g, b] 1/m), phase, g, model ("simplified" | "physical"),
//               a0, a1
//   [beamtree]  max_outer_planes (0 = full convex hulls, else 8..), automatic_inner (bool),
//               pieces (bool, default false: convex pieces where a hull is loose; with full
//               hulls only)
//   [environment]  image-based lighting (ibl/): file (a studio light's name, e.g. "courtyard",
//               from SceneSearchPaths::environments, or an equirectangular .exr relative to this
//               file), intensity, rotation (degrees about +y), face_size (power of two),
//               prefilter ("importance" | "cone"), distribution ("ggx" | "beckmann"), samples,
//               filtered (bool), shading ("split-sum" | "moschos"), skybox (bool), enabled
//               (bool: false turns a base scene's environment off)
//   [materials.NAME]  albedo, roughness (microfacet α), f0 = [r, g, b], casts_shadow (bool,
//               default true; false: glass, seen but passed by the light); translucent (sss/): a
//               preset name (sss::material_preset) or "custom" with sigma_s_reduced, sigma_a
//               ([r, g, b] 1/mm) and eta; model ("dipole" | "multipole"); coats = [{ material =
//               a preset, thickness = mm }, ...] (layers above the material, top first)
//   [sss]       subsurface splatting: mm_per_unit, grid = [N, M], jitter (bool), map_size,
//               epsilon, radius ("flux" | "profile"), footprint (bool), weighting ("jacobian" |
//               "seed"), profile_texels, environment_samples; [[sss.lights]] fill lights for the
//               translucent objects, each with the keys of [light]
//   [[objects]] name, shape ("mesh" | "box" | "sphere" | "cylinder" | "torus" | "plane"),
//               the shape's parameters, material, translate, rotate (degrees about x, y, z,
//               applied in that order), scale (number or [x, y, z]),
//               inner = [{ min = [..], max = [..] }, ...]   (boxes in the local frame)
//   [[models]]  a whole model read through assimp (scenes/model.h): file (any format assimp
//               reads, looked up as meshes are), name (prefix of the objects' names, default the
//               file's stem), translate, rotate, scale (the whole model); drop = ["glob", ...]
//               (parts whose node or material name matches are left out), glass = ["glob",
//               ...] (the parts that cast no shadow; default: those whose file material is not
//               opaque), materials = { "glob" = "scene material" } (retag parts). Each (node,
//               mesh) pair becomes an object "<name>/<node>" with its node's transform.
//   [animation] keyframed tracks of the light, the camera and the objects (scenes/animation.h)

#include <filesystem>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sl {

struct SceneSearchPaths {
    std::filesystem::path scenes;        // canonical scene files (<name>.toml)
    std::filesystem::path data;          // extracted meshes (data/meshes/*.off)
    std::filesystem::path environments;  // HDR environments (<name>.exr), Blender's studio lights
    // Built-in defaults, overridden by the environment variables SHAFTLAB_SCENES, SHAFTLAB_DATA,
    // SHAFTLAB_ENVIRONMENTS.
    static SceneSearchPaths defaults();
};

Scene load_scene_file(const std::filesystem::path& path, const SceneSearchPaths& paths);
// An environment as a scene file or the command line names it: an .exr (or any path with a '/')
// relative to `dir`, else a studio light's name in paths.environments. Existence is not checked.
std::filesystem::path environment_file(const std::string& name, const std::filesystem::path& dir,
                                       const SceneSearchPaths& paths);
// `origin` names the text in error messages (a path or "multiple:40").
Scene parse_scene(const std::string& text, const std::string& origin,
                  const std::filesystem::path& base_dir, const SceneSearchPaths& paths);

// A scene file that derives from `base` (`[scene] base = ...`: a canonical name, multiple:N or a
// file) and sets the scene's camera, light and medium, every value written so that it reads back
// to the same float: how the viewer saves a view of a scene.
std::string scene_view_toml(const Scene& scene, const std::string& base, const std::string& name);

// The canonical scenes in display order, and the generated `multiple:N` family.
std::vector<std::string> canonical_scene_names();
// The canonical animated scenes (toplight-orbit, parallel-walk, multiple-moving: docs/design.md
// §10), loadable by name.
std::vector<std::string> animated_scene_names();
// The effect scenes (IBL, SSS), loadable by name like the canonical ones.
std::vector<std::string> effect_scene_names();
// Real models read through assimp (house: the FZK-Haus IFC; house-sweep: its light moving;
// engine: a glTF mechanical assembly; engine-orbit: its light circling above it).
std::vector<std::string> real_scene_names();
// Scenes of other lights than one spot (docs/design.md §17; room: a point light in a room;
// parallel-lamps: a row of four spot lamps over parallel's corridor).
std::vector<std::string> light_scene_names();
// Every scene that loads by name from scenes/: the canonical, the animated, the effect, the real
// and the light scenes, in that order (`shaftlab scenes` lists them; the generated families are not
// among them).
std::vector<std::string> named_scene_names();
// A scene of N objects on a jittered grid under one spot light (docs/design.md §5), as TOML text,
// deterministic in N. `multiple` is multiple:kMultipleDefaultCount.
constexpr int kMultipleDefaultCount = 32;
// The largest N: 2·10^4 objects (about 130,000 light-facing hull faces, the 10^5 polygons of the
// tree's scaling study) keeps a scene's volumes to seconds.
constexpr int kMultipleMaxCount = 20000;
std::string generate_multiple_scene(int count);
// A few rotated boxes (their own bounding volumes) and a floor under a random spot light in a
// random medium, the eye inside the cone on odd seeds, as TOML text, deterministic in the seed:
// where the region methods must equal the reference.
constexpr int kBoxesMaxSeed = 1000000;
std::string generate_boxes_scene(int seed);
// Whether `name` names a generated scene (multiple:N or boxes:SEED), and its TOML text (an error
// naming the allowed range, or the families, otherwise).
bool is_generated_scene_name(const std::string& name);
std::string generated_scene_text(const std::string& name);

// Resolves a canonical name ("toplight"), a generated name ("multiple:120", "boxes:7") or a
// file path.
Scene load_scene(const std::string& name_or_path, const SceneSearchPaths& paths);

}  // namespace sl
