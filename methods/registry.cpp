#include "methods/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <functional>
#include <utility>

#include "analytic/beamtree_method.h"
#include "core/error.h"
#include "epipolar/epipolar.h"
#include "froxel/froxel.h"
#include "lightvolume/light_volume.h"
#include "reference/reference_method.h"
#include "sampling/march.h"
#include "sampling/planes.h"

namespace sl::methods {

namespace {

using Factory = std::function<std::unique_ptr<frame::VolumeMethod>()>;

const std::vector<std::pair<std::string, Factory>>& registry() {
    using sampling::MarchVariant;
    using sampling::PlanesVariant;
    static const std::vector<std::pair<std::string, Factory>> methods = {
        {"none", frame::create_no_volume},
        {"beamtree", analytic::create_beamtree_method},
        {"planes", [] { return sampling::create_planes_method(PlanesVariant::planes); }},
        {"hybrid1", [] { return sampling::create_planes_method(PlanesVariant::hybrid1); }},
        {"hybrid2", [] { return sampling::create_planes_method(PlanesVariant::hybrid2); }},
        {"march", [] { return sampling::create_march_method(MarchVariant::march); }},
        {"hybrid3", [] { return sampling::create_march_method(MarchVariant::hybrid3); }},
        {"froxel", froxel::create_froxel_method},
        {"lightvolume", lightvolume::create_light_volume_method},
        {"epipolar", epipolar::create_epipolar_method},
        {"reference", reference::create_reference_method},
    };
    return methods;
}

}  // namespace

std::vector<std::string> volume_method_names() {
    std::vector<std::string> names;
    for (const auto& [name, factory] : registry()) {
        names.push_back(name);
    }
    return names;
}

std::unique_ptr<frame::VolumeMethod> create_volume_method(const std::string& name) {
    for (const auto& [known, factory] : registry()) {
        if (known == name) {
            return factory();
        }
    }
    fail("unknown method {} (known: {})", quote(name), fmt::join(volume_method_names(), ", "));
}

}  // namespace sl::methods
