#pragma once
// The table of volumetric methods by name (docs/adding-a-method.md). Each method family fills it
// from its own folder: a `register_methods(frame::MethodRegistry&)` function beside its methods,
// named once in the family's CMakeLists.txt with shaftlab_method_family(), which methods/ turns
// into the one table the renderer, the harness and the viewer create methods from
// (methods/registry.h). Adding a method touches its folder alone.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "frame/volume_method.h"

namespace sl::frame {

class MethodRegistry {
public:
    using Factory = std::function<std::unique_ptr<VolumeMethod>()>;

    // `order` places the method in listings and tables (lower first; ties by name). Throws
    // sl::Error when the name is taken, or the factory makes a method of another name.
    void add(std::string name, int order, Factory create);

    // The names, in display order.
    std::vector<std::string> names() const;
    // Throws sl::Error naming the known methods (and the nearest, for a slip) when `name` is not
    // one of them.
    std::unique_ptr<VolumeMethod> create(const std::string& name) const;

private:
    struct Entry {
        std::string name;
        int order = 0;
        Factory create;
    };
    std::vector<Entry> entries_;  // kept in display order
};

// The family of `none` (this folder's): the frame without a medium.
void register_methods(MethodRegistry& registry);

}  // namespace sl::frame
