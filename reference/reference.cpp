#include "reference/reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"

namespace sl::reference {

using analytic::dvec3;

ReferenceRenderer::ReferenceRenderer(const Scene& scene) : scene_(scene) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) {
        fail("Embree could not create a device");
    }
    // Two scenes: everything for the camera's rays, the shadow casters for the light's (glass,
    // Material::casts_shadow = false, is seen but lets the light through).
    // Without glass the two are one scene, built once.
    const bool glass = std::any_of(scene.objects.begin(), scene.objects.end(),
                                   [&](const Object& o) { return !scene.casts_shadow(o); });
    rtc_scene_ = rtcNewScene(device_);
    shadow_scene_ = glass ? rtcNewScene(device_) : rtc_scene_;
    for (RTCScene target : {rtc_scene_, shadow_scene_}) {
        rtcSetSceneFlags(target, RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(target, RTC_BUILD_QUALITY_HIGH);
    }
    for (const Object& object : scene.objects) {
        const Mesh& mesh = *object.mesh;
        RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    3 * sizeof(float), mesh.positions.size()));
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const glm::vec4 p = object.transform * glm::vec4(mesh.positions[i], 1.0f);
            vertices[3 * i] = p.x;
            vertices[3 * i + 1] = p.y;
            vertices[3 * i + 2] = p.z;
        }
        auto* indices = static_cast<unsigned*>(
            rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(unsigned), mesh.triangles.size()));
        std::memcpy(indices, mesh.triangles.data(), mesh.triangles.size() * 3 * sizeof(unsigned));
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(rtc_scene_, geometry);  // ids follow the objects' indices
        if (glass && scene.casts_shadow(object)) {
            rtcAttachGeometry(shadow_scene_, geometry);
        }
        rtcReleaseGeometry(geometry);
    }
    rtcCommitScene(rtc_scene_);
    if (glass) {
        rtcCommitScene(shadow_scene_);
    }
}

ReferenceRenderer::~ReferenceRenderer() {
    if (shadow_scene_ != rtc_scene_) {
        rtcReleaseScene(shadow_scene_);
    }
    rtcReleaseScene(rtc_scene_);
    rtcReleaseDevice(device_);
}

namespace {

RTCRay make_ray(const dvec3& origin, const dvec3& direction, double t_near, double t_far) {
    RTCRay ray{};
    ray.org_x = float(origin.x);
    ray.org_y = float(origin.y);
    ray.org_z = float(origin.z);
    ray.dir_x = float(direction.x);
    ray.dir_y = float(direction.y);
    ray.dir_z = float(direction.z);
    ray.tnear = float(t_near);
    ray.tfar = float(t_far);
    ray.mask = 0xFFFFFFFFu;
    return ray;
}

}  // namespace

RTCRayHit ReferenceRenderer::intersect(const analytic::EyeRay& ray, double far) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit hit{};
    hit.ray = make_ray(ray.origin, ray.direction, 0.0, far);
    hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(rtc_scene_, &context, &hit);
    return hit;
}

double ReferenceRenderer::first_hit(const analytic::EyeRay& ray, double far) const {
    const RTCRayHit hit = intersect(ray, far);
    return hit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? far : double(hit.ray.tfar);
}

std::optional<ReferenceRenderer::SurfaceHit> ReferenceRenderer::first_surface(
    const analytic::EyeRay& ray, double far) const {
    const RTCRayHit hit = intersect(ray, far);
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        return std::nullopt;
    }
    const Object& object = scene_.objects[hit.hit.geomID];
    const Mesh& mesh = *object.mesh;
    const glm::uvec3 triangle = mesh.triangles[hit.hit.primID];
    const float u = hit.hit.u, v = hit.hit.v;
    const glm::vec3 local = (1.0f - u - v) * mesh.normals[triangle.x] +
                            u * mesh.normals[triangle.y] + v * mesh.normals[triangle.z];
    glm::vec3 normal = glm::normalize(glm::mat3(glm::inverseTranspose(object.transform)) * local);
    const glm::vec3 geometric(hit.hit.Ng_x, hit.hit.Ng_y, hit.hit.Ng_z);
    if (glm::dot(geometric, glm::vec3(ray.direction)) > 0.0f) {
        normal = -normal;  // the back of an open surface, seen from the camera's side
    }
    return SurfaceHit{double(hit.ray.tfar), int(hit.hit.geomID), normal};
}

bool ReferenceRenderer::occluded(const dvec3& from, const dvec3& to) const {
    const dvec3 d = to - from;
    const double length = glm::length(d);
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Start a hair off the sample point so that a point on a surface does not shadow itself.
    RTCRay ray = make_ray(from, d / length, 1e-5 * length, length * (1.0 - 1e-6));
    rtcOccluded1(shadow_scene_, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

bool ReferenceRenderer::occluded_towards(const dvec3& from, const dvec3& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // The hair off the point as `occluded` takes it, relative to the scene's size here.
    RTCRay ray = make_ray(from, direction, 1e-5 * std::max(1.0, glm::length(from)),
                          std::numeric_limits<float>::infinity());
    rtcOccluded1(shadow_scene_, &context, &ray);
    return ray.tfar == -std::numeric_limits<float>::infinity();
}

namespace {

// ∫ over `span` of the integrand `integral(z0, z1)` where the light at L is visible: visibility
// at both ends (a hair inside) and at stratified points between; each change between neighbours
// is refined by bisection to the tolerance.
template <typename Occluded, typename Integral>
dvec3 lit_part(const analytic::EyeRay& ray, analytic::Interval span,
               const ReferenceOptions& options, const Occluded& occluded,
               const Integral& integral) {
    auto lit = [&](double z) { return !occluded(ray.origin + z * ray.direction); };
    const int n = std::max(2, options.shadow_samples);
    const double step = (span.end - span.begin) / n;
    const double hair = 0.5 * std::min(step, options.transition_tolerance);
    dvec3 total(0.0);
    double start = span.begin, previous_z = span.begin + hair;
    bool state = lit(previous_z);
    for (int k = 0; k <= n; ++k) {
        const double z = k < n ? span.begin + (k + 0.5) * step : span.end - hair;
        const bool current = lit(z);
        if (current != state) {
            double a = previous_z, b = z;
            while (b - a > options.transition_tolerance) {
                const double m = 0.5 * (a + b);
                (lit(m) == state ? a : b) = m;
            }
            const double transition = 0.5 * (a + b);
            if (state) {
                total += integral(start, transition);
            }
            start = transition;
            state = current;
        }
        previous_z = z;
    }
    if (state) {
        total += integral(start, span.end);
    }
    return total;
}

}  // namespace

dvec3 ReferenceRenderer::in_scattering(const analytic::EyeRay& ray, double t_max,
                                       const ReferenceOptions& options) const {
    // I_s sums over the scene's lights as declared: a point light whole (its cube shell, no
    // cone), not as the six faces the methods take, so that the two can be compared.
    dvec3 total(0.0);
    for (const LightSource& source : scene_.light_sources()) {
        if (const auto* spot = std::get_if<SpotLight>(&source)) {
            const analytic::Interval span = analytic::light_interval(ray, *spot, t_max);
            if (span.empty()) {
                continue;
            }
            const dvec3 L(spot->position);
            total += lit_part(
                ray, span, options, [&](const dvec3& p) { return occluded(p, L); },
                [&](double z0, double z1) {
                    return analytic::in_scattering(ray, z0, z1, *spot, scene_.medium);
                });
            continue;
        }
        if (const auto* sun = std::get_if<DirectionalLight>(&source)) {
            // Its beams' box; shadow rays run back along the beams, out of the scene.
            const SpotLight beam = sun->beam();
            const analytic::Interval span = analytic::light_interval(ray, beam, t_max);
            if (span.empty()) {
                continue;
            }
            const dvec3 towards = -glm::normalize(dvec3(beam.direction()));
            total += lit_part(
                ray, span, options, [&](const dvec3& p) { return occluded_towards(p, towards); },
                [&](double z0, double z1) {
                    return analytic::in_scattering(ray, z0, z1, beam, scene_.medium);
                });
            continue;
        }
        const PointLight& point = std::get<PointLight>(source);
        const dvec3 L(point.position);
        analytic::Interval parts[2];
        const int count = analytic::point_light_intervals(ray, point, t_max, parts);
        for (int i = 0; i < count; ++i) {
            total += lit_part(
                ray, parts[i], options, [&](const dvec3& p) { return occluded(p, L); },
                [&](double z0, double z1) {
                    return analytic::in_scattering(ray, z0, z1, point, scene_.medium);
                });
        }
    }
    return total;
}

Image ReferenceRenderer::render(int width, int height, const ReferenceOptions& options,
                                const std::function<void(double)>& progress) const {
    const dvec3 eye(scene_.camera.position);
    const PixelUnprojector pixels(scene_.camera, width, height);
    Image image(width, height);
    std::atomic<int> rows_done = 0;
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const dvec3 far = pixels.point(x, y, 1.0);
            const analytic::EyeRay ray{eye, glm::normalize(far - eye)};
            const double t_max = first_hit(ray, glm::length(far - eye));
            image.set(x, y, glm::vec3(in_scattering(ray, t_max, options)));
        }
        const int done = ++rows_done;
        if (progress) {
            progress(double(done) / height);
        }
    });
    return image;
}

std::vector<uint8_t> same_surface_pixels(const Scene& scene, int width, int height,
                                         const std::vector<float>& window_depth) {
    if (window_depth.size() != size_t(width) * size_t(height)) {
        fail("a depth buffer of {} pixels for a {}x{} frame", window_depth.size(), width, height);
    }
    const ReferenceRenderer caster(scene);
    const dvec3 eye(scene.camera.position);
    const PixelUnprojector pixels(scene.camera, width, height);
    std::vector<uint8_t> same(window_depth.size(), 0);
    tbb::parallel_for(0, height, [&](int y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = size_t(y) * size_t(width) + size_t(x);
            const dvec3 far = pixels.point(x, y, 1.0);
            const analytic::EyeRay ray{eye, glm::normalize(far - eye)};
            const double cast = caster.first_hit(ray, glm::length(far - eye));
            const double depth = double(window_depth[i]);
            const double drawn = depth < 1.0
                                     ? glm::length(pixels.point(x, y, 2.0 * depth - 1.0) - eye)
                                     : glm::length(far - eye);
            same[i] = std::abs(cast - drawn) <= 1e-3 * std::max(cast, drawn) ? 1 : 0;
        }
    });
    return same;
}

uint64_t reference_key(const Scene& scene, int width, int height, const ReferenceOptions& options) {
    // FNV-1a over the bytes of every input.
    uint64_t hash = 1469598103934665603ull;
    auto mix = [&](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) {
            hash = (hash ^ p[i]) * 1099511628211ull;
        }
    };
    auto mix_value = [&](const auto& value) { mix(&value, sizeof(value)); };
    const char version[] = "shaftlab-reference-2";
    mix(version, sizeof(version));
    mix_value(width);
    mix_value(height);
    mix_value(options.shadow_samples);
    mix_value(options.transition_tolerance);
    const Camera& c = scene.camera;
    for (const float v : {c.position.x, c.position.y, c.position.z, c.target.x, c.target.y,
                          c.target.z, c.up.x, c.up.y, c.up.z, c.fov_y_degrees, c.near, c.far}) {
        mix_value(v);
    }
    for (const LightSource& source : scene.light_sources()) {
        if (const auto* l = std::get_if<SpotLight>(&source)) {
            for (const float v :
                 {l->position.x, l->position.y, l->position.z, l->target.x, l->target.y,
                  l->target.z, l->cone_half_angle_degrees, l->near, l->far, l->intensity.r,
                  l->intensity.g, l->intensity.b, l->falloff_degrees}) {
                mix_value(v);
            }
            if (l->shape != SpotShape::cone) {
                mix_value(l->shape);  // a cone hashes as before shapes existed: caches stay valid
            }
        } else if (const auto* sun = std::get_if<DirectionalLight>(&source)) {
            mix_value(0x5u);  // a directional light
            for (const float v :
                 {sun->direction.x, sun->direction.y, sun->direction.z, sun->irradiance.r,
                  sun->irradiance.g, sun->irradiance.b, sun->entry.x, sun->entry.y, sun->entry.z,
                  sun->region.min.x, sun->region.min.y, sun->region.min.z, sun->region.max.x,
                  sun->region.max.y, sun->region.max.z}) {
                mix_value(v);
            }
        } else {
            const PointLight& p = std::get<PointLight>(source);
            mix_value(0xB01D1u);  // a point light, apart from any spot light
            for (const float v : {p.position.x, p.position.y, p.position.z, p.near, p.far,
                                  p.intensity.r, p.intensity.g, p.intensity.b}) {
                mix_value(v);
            }
        }
    }
    const Medium& m = scene.medium;
    for (const float v : {m.sigma_s.r, m.sigma_s.g, m.sigma_s.b, m.sigma_a.r, m.sigma_a.g,
                          m.sigma_a.b, m.g, m.a0, m.a1}) {
        mix_value(v);
    }
    mix_value(m.phase);
    mix_value(m.model);
    for (const Object& object : scene.objects) {
        mix_value(object.transform);
        mix_value(scene.casts_shadow(object));
        mix(object.mesh->positions.data(), object.mesh->positions.size() * sizeof(glm::vec3));
        mix(object.mesh->triangles.data(), object.mesh->triangles.size() * sizeof(glm::uvec3));
    }
    return hash;
}

}  // namespace sl::reference
