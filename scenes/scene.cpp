#include "scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

#include "core/check.h"
#include "core/error.h"

namespace sl {

glm::mat4 Placement::matrix() const {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate);
    m = glm::rotate(m, glm::radians(rotate_degrees.z), {0, 0, 1});
    m = glm::rotate(m, glm::radians(rotate_degrees.y), {0, 1, 0});
    m = glm::rotate(m, glm::radians(rotate_degrees.x), {1, 0, 0});
    return glm::scale(m, scale);
}

glm::mat4 Camera::view() const {
    return glm::lookAt(position, target, up);
}

glm::mat4 Camera::projection(float aspect) const {
    return glm::perspective(glm::radians(fov_y_degrees), aspect, near, far);
}

PixelUnprojector::PixelUnprojector(const Camera& camera, int width, int height)
    : inverse_(glm::inverse(glm::dmat4(camera.projection(float(width) / float(height))) *
                            glm::dmat4(camera.view()))),
      width_(width),
      height_(height) {}

glm::dvec3 PixelUnprojector::point(int x, int y, double ndc_z) const {
    const glm::dvec4 p = inverse_ * glm::dvec4(2.0 * (x + 0.5) / width_ - 1.0,
                                               1.0 - 2.0 * (y + 0.5) / height_, ndc_z, 1.0);
    return glm::dvec3(p) / p.w;
}

glm::vec3 SpotLight::direction() const {
    return glm::normalize(target - position);
}

glm::vec3 SpotLight::up() const {
    const glm::vec3 d = direction();
    return std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, -1);
}

glm::mat4 SpotLight::view() const {
    return glm::lookAt(position, target, up());
}

glm::mat4 SpotLight::projection() const {
    if (parallel()) {
        return glm::ortho(-half_width, half_width, -half_width, half_width, near, far);
    }
    // A square frustum of half-angle θ circumscribes the cone of half-angle θ.
    return glm::perspective(2.0f * glm::radians(cone_half_angle_degrees), 1.0f, near, far);
}

namespace {

// SpotLight::cone_factor in the precision of T.
template <typename T>
T cone_factor_in(const SpotLight& light, const glm::vec<3, T>& p) {
    using V = glm::vec<3, T>;
    if (light.parallel()) {
        // Inside the box's four sides, beyond the entry plane.
        const V d = glm::normalize(V(light.direction()));
        const V u = glm::normalize(V(light.up()) - glm::dot(V(light.up()), d) * d);
        const V r = glm::cross(d, u);
        const V q = p - V(light.position);
        const T w = T(light.half_width);
        return glm::dot(q, d) >= T(0) && std::abs(glm::dot(q, r)) <= w &&
                       std::abs(glm::dot(q, u)) <= w
                   ? T(1)
                   : T(0);
    }
    if (light.shape == SpotShape::pyramid) {
        // Inside the four sides: |x| and |y| in the light's frame at most tan θ times the depth.
        const V d = glm::normalize(V(light.direction()));  // as analytic::pyramid_interval's
        const V u = glm::normalize(V(light.up()) - glm::dot(V(light.up()), d) * d);
        const V r = glm::cross(d, u);
        const V q = p - V(light.position);
        const T depth = glm::dot(q, d);
        const T reach = T(std::tan(glm::radians(double(light.cone_half_angle_degrees)))) * depth;
        return depth > T(0) && std::abs(glm::dot(q, r)) <= reach &&
                       std::abs(glm::dot(q, u)) <= reach
                   ? T(1)
                   : T(0);
    }
    const T cos_angle = glm::dot(glm::normalize(p - V(light.position)), V(light.direction()));
    const T angle = glm::degrees(std::acos(std::clamp(cos_angle, T(-1), T(1))));
    const T cone = T(light.cone_half_angle_degrees), falloff = T(light.falloff_degrees);
    if (falloff <= T(0)) {
        return angle <= cone ? T(1) : T(0);  // Nilsson eq. 2.9
    }
    const T t = std::clamp((cone - angle) / falloff, T(0), T(1));
    return t * t * (T(3) - T(2) * t);  // smoothstep from the edge inwards
}

}  // namespace

float SpotLight::cone_factor(glm::vec3 p) const {
    return cone_factor_in(*this, p);
}

double SpotLight::cone_factor(const glm::dvec3& p) const {
    return cone_factor_in(*this, p);
}

bool SpotLight::in_influence_volume(glm::vec3 p) const {
    const glm::vec4 clip = projection() * view() * glm::vec4(p, 1.0f);
    return clip.w > 0.0f && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w &&
           std::abs(clip.z) <= clip.w;
}

glm::vec3 Medium::transmittance(float s) const {
    if (model == MediumModel::simplified) {
        return glm::vec3(1.0f);
    }
    return glm::exp(-sigma_t() * s);
}

glm::vec3 Medium::light_falloff(float r) const {
    if (model == MediumModel::simplified) {
        return glm::vec3(1.0f / (a1 * r * r + a0));
    }
    return transmittance(r) / (r * r);
}

bool distinct_in_float(glm::vec3 from, glm::vec3 to) {
    const glm::dvec3 a(from), b(to);
    const double scale = std::max({1.0, glm::length(a), glm::length(b)});
    return glm::length(b - a) > 1e-5 * scale;
}

std::array<SpotLight, 6> PointLight::faces() const {
    // The target one step along the axis changes one coordinate alone, so that the direction is
    // the axis to the last bit wherever the light is.
    const float step = std::max(1.0f, 2.0f * glm::length(position));
    const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::array<SpotLight, 6> faces;
    for (size_t i = 0; i < 6; ++i) {
        SpotLight& face = faces[i];
        face.position = position;
        face.target = position + step * axes[i];
        face.cone_half_angle_degrees = 45.0f;
        face.near = near;
        face.far = far;
        face.intensity = intensity;
        face.falloff_degrees = 0.0f;
        face.shape = SpotShape::pyramid;
        face.cube_face = true;
    }
    return faces;
}

bool PointLight::in_range(const glm::dvec3& p) const {
    const glm::dvec3 q = glm::abs(p - glm::dvec3(position));
    const double extent = std::max({q.x, q.y, q.z});
    return extent >= double(near) && extent <= double(far);
}

SpotLight DirectionalLight::beam() const {
    SpotLight beam;
    const glm::dvec3 d = glm::normalize(glm::dvec3(direction));
    // The axis through the region's centre, from the entry plane; up as SpotLight::up picks it.
    const glm::dvec3 centre = 0.5 * (glm::dvec3(region.min) + glm::dvec3(region.max));
    const glm::dvec3 position = centre - glm::dot(centre - glm::dvec3(entry), d) * d;
    beam.position = glm::vec3(position);
    const float step = std::max(1.0f, 2.0f * glm::length(beam.position));
    beam.target = beam.position + step * glm::vec3(d);
    const glm::dvec3 up(beam.up());
    const glm::dvec3 u = glm::normalize(up - glm::dot(up, d) * d);
    const glm::dvec3 r = glm::cross(d, u);
    double width = 0.0, depth = 0.0;
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 q = glm::dvec3(region.corner(i)) - position;
        width = std::max({width, std::abs(glm::dot(q, r)), std::abs(glm::dot(q, u))});
        depth = std::max(depth, glm::dot(q, d));
    }
    // A hair wider and deeper than the region, so that its corners are inside in float.
    beam.half_width = float(width * (1.0 + 1e-5) + 1e-6);
    beam.near = 0.0f;
    beam.far = float(depth * (1.0 + 1e-5) + 1e-6);
    beam.cone_half_angle_degrees = 0.0f;
    beam.intensity = irradiance;
    beam.shape = SpotShape::pyramid;
    return beam;
}

void DirectionalLight::enter_region() {
    const glm::dvec3 d(direction);
    double nearest = std::numeric_limits<double>::max();
    for (int i = 0; i < 8; ++i) {
        const double along = glm::dot(glm::dvec3(region.corner(i)), d);
        if (along < nearest) {
            nearest = along;
            entry = region.corner(i);
        }
    }
}

const char* light_type(const LightSource& light) {
    if (std::holds_alternative<SpotLight>(light)) {
        return "spot";
    }
    return std::holds_alternative<PointLight>(light) ? "point" : "directional";
}

std::vector<LightSource> Scene::light_sources() const {
    if (lights.empty()) {
        return {light};
    }
    return lights;
}

namespace {

// Spot lights as they are, point lights as their six faces, directional lights as their beams,
// in order.
std::vector<SpotLight> spots_of(const std::vector<LightSource>& sources) {
    std::vector<SpotLight> spots;
    for (const LightSource& source : sources) {
        if (const auto* spot = std::get_if<SpotLight>(&source)) {
            spots.push_back(*spot);
        } else if (const auto* sun = std::get_if<DirectionalLight>(&source)) {
            spots.push_back(sun->beam());
        } else {
            const std::array<SpotLight, 6> faces = std::get<PointLight>(source).faces();
            spots.insert(spots.end(), faces.begin(), faces.end());
        }
    }
    return spots;
}

}  // namespace

std::vector<SpotLight> Scene::spot_lights() const {
    if (lights.empty()) {
        return {light};
    }
    std::vector<SpotLight> spots = spots_of(lights);
    SL_CHECK(!spots.empty() && spots.front() == light);  // as set_lights() left them
    return spots;
}

Scene Scene::for_light(size_t index) const {
    const std::vector<SpotLight> spots = spot_lights();
    SL_CHECK_INDEX(index, spots.size());
    Scene view = *this;
    view.light = spots[index];
    view.lights.clear();
    return view;
}

void Scene::set_lights(std::vector<LightSource> sources) {
    if (sources.empty()) {
        fail("a scene needs at least one light");
    }
    if (sources.size() == 1 && std::holds_alternative<SpotLight>(sources.front())) {
        light = std::get<SpotLight>(sources.front());
        lights.clear();
        return;
    }
    light = spots_of(sources).front();
    lights = std::move(sources);
}

size_t Scene::triangle_count() const {
    size_t count = 0;
    for (const Object& object : objects) {
        count += object.mesh->triangles.size();
    }
    return count;
}

bool Scene::has_translucent_objects() const {
    for (const Object& object : objects) {
        if (materials[size_t(object.material)].translucency) {
            return true;
        }
    }
    return false;
}

const char* to_string(PhaseFunction phase) {
    switch (phase) {
        case PhaseFunction::isotropic:
            return "isotropic";
        case PhaseFunction::henyey_greenstein:
            return "henyey-greenstein";
        case PhaseFunction::schlick:
            return "schlick";
        case PhaseFunction::rayleigh:
            return "rayleigh";
        case PhaseFunction::mie_hazy:
            return "mie-hazy";
        case PhaseFunction::mie_murky:
            return "mie-murky";
        case PhaseFunction::nishita_hazy:
            return "nishita-hazy";
    }
    return "?";
}

const char* to_string(MediumModel model) {
    return model == MediumModel::simplified ? "simplified" : "physical";
}

const char* to_string(DiffusionModel model) {
    return model == DiffusionModel::dipole ? "dipole" : "multipole";
}

const char* to_string(SplatWeighting weighting) {
    return weighting == SplatWeighting::jacobian ? "jacobian" : "seed";
}

const char* to_string(Occluders occluders) {
    switch (occluders) {
        case Occluders::volumes:
            return "volumes";
        case Occluders::triangles:
            return "triangles";
        case Occluders::automatic:
            return "auto";
    }
    return "?";
}

bool Scene::casts_shadow(const Object& object) const {
    return object.material < 0 || size_t(object.material) >= materials.size() ||
           materials[size_t(object.material)].casts_shadow;
}

}  // namespace sl
