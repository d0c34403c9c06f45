#include "gl/volume_method.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <functional>
#include <map>

#include "core/error.h"

namespace sl::gl {

namespace {

// `none`: no participating medium is rendered, I_s = 0; the frame is the surfaces alone
// (I_obj·T(Z)). The baseline every method's cost is measured against.
class NoVolume final : public VolumeMethod {
public:
    std::string name() const override { return "none"; }
    void prepare(const Scene&) override {}
    void render(const VolumeInputs&) override {}
};

using Factory = std::function<std::unique_ptr<VolumeMethod>()>;

const std::vector<std::pair<std::string, Factory>>& registry() {
    static const std::vector<std::pair<std::string, Factory>> methods = {
        {"none", [] { return std::make_unique<NoVolume>(); }},
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

std::unique_ptr<VolumeMethod> create_volume_method(const std::string& name) {
    for (const auto& [known, factory] : registry()) {
        if (known == name) {
            return factory();
        }
    }
    fail("unknown method '{}' (known: {})", name, fmt::join(volume_method_names(), ", "));
}

}  // namespace sl::gl
