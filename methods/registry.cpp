#include "methods/registry.h"

#include "methods/method_families.h"

namespace sl::methods {

namespace {

const frame::MethodRegistry& registry() {
    static const frame::MethodRegistry table = [] {
        frame::MethodRegistry r;
        register_method_families(r);
        return r;
    }();
    return table;
}

}  // namespace

std::vector<std::string> volume_method_names() {
    return registry().names();
}

std::unique_ptr<frame::VolumeMethod> create_volume_method(const std::string& name) {
    return registry().create(name);
}

}  // namespace sl::methods
