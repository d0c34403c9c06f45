#include "reference/environment_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "ibl/shading.h"
#include "reference/reference.h"

namespace sl::reference {

Scene environment_only_scene(const Scene& scene) {
    Scene only = scene;
    only.light.intensity = glm::vec3(0.0f);
    only.lights.clear();  // every light off: `light` alone, dark
    only.medium.sigma_s = glm::vec3(0.0f);
    only.medium.sigma_a = glm::vec3(0.0f);
    only.ambient = glm::vec3(0.0f);
    return only;
}

Image render_environment_reference(const Scene& scene, const ibl::LoadedEnvironment& environment,
                                   int width, int height,
                                   const EnvironmentReferenceOptions& options,
                                   std::vector<int>* object_ids) {
    if (!scene.environment.enabled()) {
        fail("scene '{}' has no [environment] to make a reference of", scene.name);
    }
    if (options.samples < 1) {
        fail("environment reference: samples {} must be at least 1", options.samples);
    }
    const ReferenceRenderer renderer(scene);
    const PixelUnprojector unproject(scene.camera, width, height);
    const double far = 1e6;
    Image image(width, height);
    if (object_ids) {
        object_ids->assign(size_t(width) * size_t(height), -1);
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y != rows.end(); ++y) {
            for (int x = 0; x < width; ++x) {
                const glm::dvec3 origin = unproject.point(x, y, -1.0);
                const glm::dvec3 direction = glm::normalize(unproject.point(x, y, 1.0) - origin);
                const std::optional<ReferenceRenderer::SurfaceHit> hit =
                    renderer.first_surface({origin, direction}, far);
                if (!hit) {
                    image.set(x, y,
                              environment.intensity *
                                  environment.chain.levels[0].sample(glm::vec3(direction)));
                    continue;
                }
                if (object_ids) {
                    (*object_ids)[size_t(y) * size_t(width) + size_t(x)] = hit->object;
                }
                const Material& material =
                    scene.materials[size_t(scene.objects[size_t(hit->object)].material)];
                const glm::dvec3 position = origin + hit->t * direction;
                const glm::dvec3 offset = position + 1e-4 * glm::dvec3(hit->normal);
                std::function<bool(glm::vec3)> visible;
                if (options.occlusion) {
                    visible = [&](glm::vec3 l) {
                        return !renderer.occluded(offset, offset + 1e3 * glm::dvec3(l));
                    };
                }
                image.set(x, y,
                          ibl::reference_environment_radiance(
                              environment, scene.environment.shading,
                              {hit->normal, -glm::vec3(direction), material.albedo,
                               material.roughness, material.f0},
                              options.samples, visible));
            }
        }
    });
    return image;
}

}  // namespace sl::reference
