#include "frame/method_registry.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/error.h"
#include "core/suggest.h"
#include "core/text.h"

namespace sl::frame {

void MethodRegistry::add(std::string name, int order, Factory create) {
    for (const Entry& entry : entries_) {
        if (entry.name == name) {
            fail("method '{}' is registered twice", name);
        }
    }
    if (const std::string made = create()->name(); made != name) {
        fail("method registered as '{}' calls itself '{}'", name, made);
    }
    Entry entry{std::move(name), order, std::move(create)};
    const auto at = std::upper_bound(
        entries_.begin(), entries_.end(), entry, [](const Entry& a, const Entry& b) {
            return a.order != b.order ? a.order < b.order : a.name < b.name;
        });
    entries_.insert(at, std::move(entry));
}

std::vector<std::string> MethodRegistry::names() const {
    std::vector<std::string> names;
    for (const Entry& entry : entries_) {
        names.push_back(entry.name);
    }
    return names;
}

std::unique_ptr<VolumeMethod> MethodRegistry::create(const std::string& name) const {
    for (const Entry& entry : entries_) {
        if (entry.name == name) {
            std::unique_ptr<VolumeMethod> method = entry.create();
            method->factory_ = entry.create;  // its copies for further lights
            return method;
        }
    }
    const std::vector<std::string> known = names();
    fail("unknown method {}{} (known: {})", quote(name), did_you_mean(name, known),
         fmt::join(known, ", "));
}

void register_methods(MethodRegistry& registry) {
    registry.add("none", 0, create_no_volume);
}

}  // namespace sl::frame
