#pragma once
// The scene every method renders: meshes with materials and transforms, one spot light, a camera
// and a homogeneous participating medium (docs/design.md §1). Plain data plus the derived
// quantities (matrices, cone factor) that the GPU and CPU paths must agree on.

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <glm/ext/matrix_double4x4.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "materials/ibl_settings.h"
#include "materials/scattering_material.h"
#include "scenes/mesh.h"

namespace sl {

enum class DiffusionModel { dipole, multipole };

// A translucent material (sss/, Rohat chapters 4-5): its diffuse term is replaced by subsurface
// scattering splatted from the lights (and the environment); the specular term stays.
struct Translucency {
    sss::ScatteringMaterial medium;  // the base material (coefficients in 1/mm)
    DiffusionModel model = DiffusionModel::dipole;
    std::vector<sss::Layer> coats;  // layers above the base, top first (Rohat §5.1.2)
};

struct Material {
    std::string name;
    glm::vec3 albedo{0.8f};  // diffuse reflectance in [0, 1]
    float roughness = 0.5f;  // microfacet α (Beckmann's m, GGX's α); used when IBL is on
    glm::vec3 f0{0.04f};     // normal-incidence specular reflectance, likewise
    std::optional<Translucency> translucency{};
    // false: glass. The light passes the surface as if it were absent (no shadow in any method,
    // the beam tree or the reference) while the camera still sees it.
    bool casts_shadow = true;
};

// An axis-aligned box in an object's local frame.
struct Box {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
    bool operator==(const Box&) const = default;
    // Corner i of 8: bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
    glm::vec3 corner(int i) const {
        return {i & 1 ? max.x : min.x, i & 2 ? max.y : min.y, i & 4 ? max.z : min.z};
    }
};

// An object's placement as scene files write it: translate, then rotate about z, y and x (degrees;
// x applied first), then scale. Animation tracks replace its parts (scenes/animation.h).
struct Placement {
    glm::vec3 translate{0.0f};
    glm::vec3 rotate_degrees{0.0f};
    glm::vec3 scale{1.0f};
    glm::mat4 matrix() const;
    bool operator==(const Placement&) const = default;
};

struct Object {
    std::string name;
    std::shared_ptr<const Mesh> mesh;  // local frame
    glm::mat4 transform{1.0f};         // local -> world: placed() for scene files
    Placement placement{};
    glm::mat4 local{1.0f};         // mesh frame -> the placement's frame (a model's node transform)
    int material = 0;              // index into Scene::materials
    std::vector<Box> inner_boxes;  // explicit inner bounding volumes, local frame

    glm::mat4 placed() const { return placement.matrix() * local; }
};

struct Camera {
    glm::vec3 position{0.0f, 1.0f, 5.0f};
    glm::vec3 target{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 45.0f;  // vertical field of view
    float near = 0.1f;
    float far = 100.0f;
    float exposure = 1.0f;  // linear scale before tone mapping

    bool operator==(const Camera&) const = default;
    glm::mat4 view() const;
    glm::mat4 projection(float aspect) const;
};

// Pixel centres of a width x height image (row 0 at the top) mapped back through the camera, in
// double precision: the one place CPU code makes eye rays the way the GPU rasterises them.
class PixelUnprojector {
public:
    PixelUnprojector(const Camera& camera, int width, int height);
    // The world point under the centre of pixel (x, y) at normalised device depth ndc_z
    // (-1: the near plane, 1: the far plane).
    glm::dvec3 point(int x, int y, double ndc_z) const;

private:
    glm::dmat4 inverse_;
    int width_;
    int height_;
};

// The emission of a spot light: a cone (Nilsson eq. 2.9) or the square pyramid circumscribing it
// (Moschos §3.2.1: "either conical or pyramidal"), whose sides are the influence pyramid's: six
// pyramids of half-angle 45° tile a point light's cube (PointLight::faces).
enum class SpotShape { cone, pyramid };

struct SpotLight {
    glm::vec3 position{0.0f, 5.0f, 0.0f};
    glm::vec3 target{0.0f};
    float cone_half_angle_degrees = 30.0f;
    float near = 0.1f;  // the influence volume spans [near, far] along the axis
    float far = 20.0f;  // the backplate: nothing is lit beyond it
    glm::vec3 intensity{1.0f};
    float falloff_degrees = 0.0f;  // 0: hard edge (Nilsson eq. 2.9); else smooth over this width
    SpotShape shape = SpotShape::cone;  // a pyramid has a hard edge (falloff 0)
    // > 0: parallel beams (a directional light's box, DirectionalLight::beam): the influence
    // volume is a square box of this half-width about the axis from `position` (on the entry
    // plane) on, `intensity` is the irradiance, the shadow map orthographic; the cone angle is
    // unused (0) and the shape a pyramid (the box's sides are the shadow map's clip square).
    float half_width = 0.0f;
    // One of a point light's six faces (PointLight::faces): its four sides are its neighbours'
    // sides, and the cube shell about its position is what the six tile.
    bool cube_face = false;

    bool operator==(const SpotLight&) const = default;
    bool parallel() const { return half_width > 0.0f; }
    // A cone with a falloff width (a pyramid's edge is always hard).
    bool smooth_edge() const { return shape == SpotShape::cone && falloff_degrees > 0.0f; }
    glm::vec3 direction() const;
    // An up vector not parallel to the axis, fixed so that the shadow map never flips.
    glm::vec3 up() const;
    glm::mat4 view() const;
    // The square frustum circumscribing the cone (the influence pyramid), near to far; for
    // parallel beams the box, orthographic.
    glm::mat4 projection() const;
    // I(Ω) / I of eq. 2.9 for the direction from the light to p, with the optional falloff (a
    // pyramid: 1 inside its four sides, 0 outside); in double precision for quadrature (float
    // would leave noise it cannot converge on).
    float cone_factor(glm::vec3 p) const;
    double cone_factor(const glm::dvec3& p) const;
    // True when p lies inside the influence pyramid between near and far.
    bool in_influence_volume(glm::vec3 p) const;
};

// A point light (docs/scenes.md): it shines every way, and scatters between two cubes centred on
// it, of half-sizes `near` and `far` (a cube map's frusta, so that its six pyramidal faces tile
// that shell exactly).
struct PointLight {
    glm::vec3 position{0.0f, 5.0f, 0.0f};
    float near = 0.1f;
    float far = 20.0f;
    glm::vec3 intensity{1.0f};  // W/sr, as a spot light's

    bool operator==(const PointLight&) const = default;
    // The six spot lights of half-angle 45° and shape pyramid, along +x, -x, +y, -y, +z, -z (a cube
    // map's faces), that sum to this light: each face's up vector (SpotLight::up) is axis-aligned,
    // so neighbouring faces share their sides.
    std::array<SpotLight, 6> faces() const;
    // True when p lies between the two cubes.
    bool in_range(const glm::dvec3& p) const;
};

// A directional light (the sun; docs/scenes.md): parallel beams along `direction` with
// `irradiance` (W/m² across the beam) where they enter the medium, at the plane through `entry`
// perpendicular to them; the light's path in the medium at x is dot(x - entry, direction). It
// scatters inside `region` beyond that plane, and its shadows fall wherever its beams go.
struct DirectionalLight {
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit: the way the light travels
    glm::vec3 irradiance{1.0f};
    glm::vec3 entry{0.0f};
    // World box where it scatters: by default the scene's objects' bounds and the camera's
    // position (docs/scenes.md), resolved when the scene is read.
    Box region{};
    // The scene gave no entry: it is the plane touching the region on the light's side, and
    // follows the direction when an animation turns it (enter_region).
    bool default_entry = false;

    bool operator==(const DirectionalLight&) const = default;
    // The region's bounding box across the beams as the spot light that every part taking one
    // light reads: SpotLight::parallel, a square of half-width covering the region about the
    // axis through its centre, from the entry plane to the region's far side.
    SpotLight beam() const;
    // Sets `entry` to the region's corner nearest the light: the plane touching it.
    void enter_region();
};

// The most spot lights a scene file may ask for, a point light counting as its six faces (each
// is its own shadow map, tree and method instance).
inline constexpr size_t kMaxSpotLights = 256;

// One light as a scene file declares it ([light], or one [[lights]] entry).
using LightSource = std::variant<SpotLight, PointLight, DirectionalLight>;
const char* light_type(const LightSource& light);  // "spot", "point", "directional"

enum class PhaseFunction {
    isotropic,
    henyey_greenstein,
    schlick,
    rayleigh,
    mie_hazy,
    mie_murky,
    nishita_hazy
};
enum class MediumModel { simplified, physical };

struct Medium {
    glm::vec3 sigma_s{0.0f};  // scattering coefficient, 1/m
    glm::vec3 sigma_a{0.0f};  // absorption coefficient, 1/m
    PhaseFunction phase = PhaseFunction::isotropic;
    float g = 0.0f;  // asymmetry parameter of Henyey-Greenstein and Schlick
    MediumModel model = MediumModel::simplified;
    float a0 = 1.0f;  // simplified model attenuation I / (a1 r^2 + a0), Nilsson eq. 2.13
    float a1 = 1.0f;

    bool operator==(const Medium&) const = default;
    glm::vec3 sigma_t() const { return sigma_s + sigma_a; }
    // T(s) along a path of length s: e^(-σt s) (Nilsson eq. 2.2) for `physical`, 1 for
    // `simplified` (eq. 2.15).
    glm::vec3 transmittance(float s) const;
    // Irradiance falloff of the light at distance r: T(r)/r² (eq. 2.8) or 1/(a1 r² + a0)
    // (eq. 2.13).
    glm::vec3 light_falloff(float r) const;
};

// How the beam tree bounds the objects ([beamtree] in scene files; beamtree/bounding_volumes.h
// computes them with these settings).
enum class Occluders { volumes, triangles, automatic };
inline constexpr Occluders kOccluders[] = {Occluders::volumes, Occluders::triangles,
                                           Occluders::automatic};
const char* to_string(Occluders occluders);  // as scene files write it: volumes, triangles, auto

struct BoundsSettings {
    int max_outer_planes = 0;     // 0: the full convex hull; else at most this many planes (>= 8)
    bool automatic_inner = true;  // find an inner box for closed meshes without explicit ones
    // Several convex hulls where one is loose (beamtree/pieces.h), each grown by 1e-4 of the
    // mesh's size. Off by default: the boundary meshes of thin grown pieces (random tori) keep a
    // few faces that separate nothing, within 1e-9 of the volume.
    bool pieces = false;
    // What each object enters the beam tree as: its bounding volumes (hulls or pieces, and inner
    // volumes); its triangles, each an exact occluder (unlit behind it, whatever the mesh's
    // winding or closedness); or, automatically, triangles for the objects whose volumes are
    // loose (first those without an inner volume, then those whose inner volumes fill less than
    // min_inner_fill of their outer volumes; smallest first within each, while the scene's total
    // stays within max_triangles) and volumes for the rest.
    Occluders occluders = Occluders::volumes;
    int max_triangles = 50000;
    double min_inner_fill = 0.5;
};

// Image-based lighting from an HDR environment (ibl/, Moschos §3.3); off when `file` is empty.
struct Environment {
    std::filesystem::path file;     // equirectangular OpenEXR, resolved when the scene is read
    float intensity = 1.0f;         // radiance scale
    float rotation_degrees = 0.0f;  // about +y
    int face_size = 256;            // the cube map's level 0, a power of two
    ibl::PrefilterSettings prefilter;
    ibl::Shading shading = ibl::Shading::split_sum;
    bool skybox = true;  // draw the environment behind the scene

    bool enabled() const { return !file.empty(); }
};

// How translucent objects are rendered ([sss] in scene files; Rohat §5.1, §5.3).
enum class SplatWeighting {
    jacobian,  // each sample carries the flux on its own patch: I·ω_texel·cone (exact eq. 4.4)
    seed       // the seed's A_vis/N_s with E(x_s) (eq. 4.6), A_vis summed over the samples
};
struct Subsurface {
    float mm_per_unit = 10.0f;  // the scene's scale for the profiles, millimetres per unit
    int grid_x = 64;            // N x M samples over the light map's region of interest
    int grid_y = 64;
    bool jitter = true;     // a random offset inside each grid cell, new every frame
    int map_size = 512;     // the light-view position/normal maps
    float epsilon = 0.01f;  // r_max: the profile's tail left out (eq. 4.3)
    // r_max's tail measured on R_d(r) 2πr dr, the reflected flux (true), or on the seed's
    // R_d(r) dr (false), which cuts marble at 6 mm where 1% of the flux is only reached at 20.
    bool flux_radius = true;
    // Each sample's profile averaged over its own patch (sss::disk_average); off: the seed's
    // point samples.
    bool footprint = true;
    SplatWeighting weighting = SplatWeighting::jacobian;
    int profile_texels = 512;
    // Environment light on translucent objects (§5.3): uniform surface samples with SH9
    // irradiance, splatted like the lights' samples; 0 turns it off.
    int environment_samples = 4096;
    // Fill lights for translucent objects only (§5.1.3), besides the scene's spot light.
    std::vector<SpotLight> lights;
};

class Animation;  // scenes/animation.h

struct Scene {
    std::string name;
    std::filesystem::path source;  // the file it was read from, empty for generated scenes
    Camera camera;
    // The light every part that takes one light reads: the scene's one spot light, or, with
    // several lights, the first of spot_lights().
    SpotLight light;
    // Several lights ([[lights]] in scene files; docs/design.md §17), as declared: empty when the
    // scene's one light is `light`. Otherwise `light` is spot_lights()[0].
    std::vector<LightSource> lights;
    Medium medium;
    // Constant incident radiance from every direction: a surface reflects albedo * ambient.
    glm::vec3 ambient{0.0f};
    BoundsSettings bounds;
    Environment environment;
    Subsurface subsurface;
    std::vector<Material> materials;
    std::vector<Object> objects;
    // Keyframed tracks ([animation] in scene files); null for a still scene. The scene's own
    // values are what the tracks leave alone.
    std::shared_ptr<const Animation> animation;

    // Every light as the methods take it, spot lights as they are, point lights as their six
    // faces and directional lights as their beams: {light} for a scene of one light. I_s is the sum
    // of each one's.
    std::vector<SpotLight> spot_lights() const;
    // The lights as declared: {light} for a scene of one light.
    std::vector<LightSource> light_sources() const;
    // This scene lit by spot_lights()[index] alone (what each light's tree, shadow map and method
    // instance see).
    Scene for_light(size_t index) const;
    // Sets `lights` and `light` together; one spot light alone is kept as `light` with `lights`
    // empty. Throws sl::Error when `sources` is empty.
    void set_lights(std::vector<LightSource> sources);

    size_t triangle_count() const;
    bool has_translucent_objects() const;
    // False for glass (Material::casts_shadow): what the shadow maps, the beam tree and the
    // reference's shadow rays leave out.
    bool casts_shadow(const Object& object) const;
};

// Two points far enough apart for float32 to give the direction between them (a camera's or a
// light's position and target): more than 1e-5 of their magnitude, at least 1e-5.
bool distinct_in_float(glm::vec3 from, glm::vec3 to);

const char* to_string(PhaseFunction phase);
const char* to_string(MediumModel model);
const char* to_string(DiffusionModel model);
const char* to_string(SplatWeighting weighting);

}  // namespace sl
