#include "frame/volume_method.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <fmt/format.h>
#include <fmt/ranges.h>

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
    void prepare(const Scene&) override {}
    std::unique_ptr<FrameWork> cpu_update(const Scene&, const SceneChange&) const override {
        return nullptr;
    }
    void apply_update(const Scene&, const SceneChange&, std::unique_ptr<FrameWork>) override {}
    void render(const VolumeInputs&) override {}
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
