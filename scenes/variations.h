#pragma once
// Named variations of a loaded scene, which the harness sweeps like method parameters
// (`[sweep.scene]`, docs/harness.md): the settings that a scene file fixes but that a study
// varies, such as Rohat's tables 6.1, 6.3 and 6.7 (splat grid, diffusion model, r_max criterion,
// camera distance). Each has one name, one kind of value, and one change to the scene.
//
//   sss_grid         "NxM"          the translucent objects' sample grid (Subsurface grid_x,
//   grid_y) sss_model        dipole | multipole   every translucent material's diffusion model
//   sss_radius       profile | flux  r_max on R_d(r) dr (the seed's eq. 4.3) or on the flux
//   sss_footprint    true | false   each sample's profile averaged over its patch, or points
//   camera_distance  a factor > 0   the camera moved along its line to the target, that factor of
//                                   its distance

#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sl {

struct SceneVariation {
    std::string name;
    std::string values;  // what it takes, for messages and docs
    // Whether it changes what the beam tree and the eye rays see (geometry, light or camera);
    // the splatting's settings do not, so the region statistics of a view are shared across them.
    bool changes_view = false;
};
const std::vector<SceneVariation>& scene_variations();
bool is_scene_variation(const std::string& name);
bool scene_variation_changes_view(const std::string& name);

// Checks `value` for the variation `name`; returns an empty string when it is fine, otherwise why
// not (naming what is allowed).
std::string scene_variation_error(const std::string& name, const std::string& value);

// `scene` with the variation applied; throws sl::Error naming the variation and what it allows.
void apply_scene_variation(Scene& scene, const std::string& name, const std::string& value);

}  // namespace sl
