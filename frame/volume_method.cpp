#include "frame/volume_method.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/check.h"
#include "core/error.h"

namespace sl::frame {

namespace {

const std::vector<std::string> kShadowFilterNames = {"hard", "pcf", "vsm"};

class NoVolume final : public VolumeMethod {
public:
    // Its shadow map is the run's unless set: a `none` paired with a method
    // (methods/frame_measurement.h) takes that method's, so the two frames differ by the volume
    // pass alone.
    NoVolume() : VolumeMethod("none") { declare_shadow_parameters(); }
    std::string accepts() const override { return "every scene (it renders no medium)"; }
    void prepare_light(const Scene&) override {}
    std::unique_ptr<FrameWork> cpu_update_light(const Scene&, const SceneChange&) const override {
        return nullptr;
    }
    void apply_update_light(const Scene&, const SceneChange&, std::unique_ptr<FrameWork>) override {
    }
    void render(const VolumeInputs&) override {}
    bool takes_every_light() const override { return true; }  // none of any of them
};

// What cpu_update() hands to apply_update() for a scene of several lights: each light's own.
struct LightsWork final : FrameWork {
    std::vector<std::unique_ptr<FrameWork>> lights;
};

}  // namespace

std::unique_ptr<VolumeMethod> create_no_volume() {
    return std::make_unique<NoVolume>();
}

const char* to_string(ShadowFilter filter) {
    return kShadowFilterNames[size_t(filter)].c_str();
}

ShadowFilter parse_shadow_filter(const std::string& text) {
    for (size_t i = 0; i < kShadowFilterNames.size(); ++i) {
        if (kShadowFilterNames[i] == text)
            return ShadowFilter(i);
    }
    fail("unknown shadow filter {} (known: {})", quote(text), fmt::join(kShadowFilterNames, ", "));
}

void VolumeMethod::declare_shadow_parameters(ShadowFilter filter) {
    shadow_filter_ = declare_choice("shadow", kShadowFilterNames, filter,
                                    "shadow map filter for mid-air visibility and surfaces");
    declare_shadow_size("shadow map resolution (texels per side)");
}

void VolumeMethod::declare_shadow_size(std::string description) {
    shadow_size_ = declare_integer("shadow_size", 2048, 16, 16384, std::move(description));
}

void VolumeMethod::set(const std::string& name, const std::string& text) {
    parameters_.set(name, text);
    for (const std::unique_ptr<VolumeMethod>& copy : copies_) {
        copy->set(name, text);
    }
}

void VolumeMethod::set_view_aspect(float aspect) {
    SL_CHECK(std::isfinite(aspect) && aspect >= 0.0f);
    view_aspect_ = aspect;
    for (const std::unique_ptr<VolumeMethod>& copy : copies_) {
        copy->set_view_aspect(aspect);
    }
}

VolumeMethod& VolumeMethod::for_light(size_t index) {
    SL_CHECK_INDEX(index, light_count());
    return index == 0 ? *this : *copies_[index - 1];
}

const VolumeMethod& VolumeMethod::for_light(size_t index) const {
    SL_CHECK_INDEX(index, light_count());
    return index == 0 ? *this : *copies_[index - 1];
}

std::unique_ptr<VolumeMethod> VolumeMethod::make_instance() const {
    if (!factory_) {
        fail(
            "method {} was not made by the method registry, so it cannot copy itself for a "
            "scene of several lights",
            quote(name_));
    }
    return factory_();
}

void VolumeMethod::prepare(const Scene& scene) {
    if (takes_every_light()) {
        copies_.clear();
        prepare_light(scene);
        return;
    }
    const size_t lights = scene.spot_lights().size();
    copies_.resize(std::min(copies_.size(), lights - 1));
    while (copies_.size() + 1 < lights) {
        std::unique_ptr<VolumeMethod> copy = make_instance();
        SL_CHECK(copy->name() == name_);
        for (const Parameter& parameter : parameters()) {
            copy->set(parameter.name, parameter.text());
        }
        copy->set_view_aspect(view_aspect_);
        copies_.push_back(std::move(copy));
    }
    for (size_t i = 0; i < lights; ++i) {
        for_light(i).prepare_light(lights == 1 ? scene : scene.for_light(i));
    }
}

std::unique_ptr<FrameWork> VolumeMethod::cpu_update(const Scene& scene,
                                                    const SceneChange& change) const {
    if (takes_every_light()) {
        return cpu_update_light(scene, change);
    }
    const size_t lights = scene.spot_lights().size();
    if (lights != light_count()) {
        return nullptr;  // apply_update() prepares again
    }
    if (lights == 1) {
        return cpu_update_light(scene, change);
    }
    // Each light on its own task: each has its own instance, which cpu_update_light() only
    // reads, and what they share (the volume library) is locked.
    auto work = std::make_unique<LightsWork>();
    work->lights.resize(lights);
    tbb::parallel_for(size_t(0), lights, [&](size_t i) {
        work->lights[i] = for_light(i).cpu_update_light(scene.for_light(i), change);
    });
    return work;
}

void VolumeMethod::apply_update(const Scene& scene, const SceneChange& change,
                                std::unique_ptr<FrameWork> work) {
    if (takes_every_light()) {
        apply_update_light(scene, change, std::move(work));
        return;
    }
    const size_t lights = scene.spot_lights().size();
    if (lights != light_count()) {
        prepare(scene);
        return;
    }
    if (lights == 1) {
        apply_update_light(scene, change, std::move(work));
        return;
    }
    auto* per_light = dynamic_cast<LightsWork*>(work.get());
    SL_CHECK(per_light && per_light->lights.size() == lights);
    for (size_t i = 0; i < lights; ++i) {
        for_light(i).apply_update_light(scene.for_light(i), change,
                                        std::move(per_light->lights[i]));
    }
}

MethodStatistics VolumeMethod::frame_statistics() const {
    MethodStatistics sum = statistics();
    if (copies_.empty()) {
        return sum;
    }
    sum.emplace_back("lights", double(light_count()));
    for (const std::unique_ptr<VolumeMethod>& copy : copies_) {
        for (const std::pair<std::string, double>& counter : copy->statistics()) {
            auto same = std::find_if(sum.begin(), sum.end(), [&](const auto& entry) {
                return entry.first == counter.first;
            });
            if (same == sum.end()) {
                sum.push_back(counter);
            } else {
                same->second += counter.second;
            }
        }
    }
    return sum;
}

ShadowSettings VolumeMethod::shadow_settings(ShadowSettings frame) const {
    if (shadow_filter_) {
        frame.filter = *shadow_filter_;
    }
    if (shadow_size_) {
        frame.map_size = *shadow_size_;
    }
    return frame;
}

}  // namespace sl::frame
