#include "materials/ibl_settings.h"

#include <fmt/format.h>

#include "core/error.h"

namespace sl::ibl {

const char* to_string(Distribution distribution) {
    return distribution == Distribution::beckmann ? "beckmann" : "ggx";
}

Distribution parse_distribution(const std::string& name) {
    if (name == "ggx")
        return Distribution::ggx;
    if (name == "beckmann")
        return Distribution::beckmann;
    fail("unknown distribution {} (expected ggx or beckmann)", quote(name));
}

const char* to_string(PrefilterMethod method) {
    return method == PrefilterMethod::cone ? "cone" : "importance";
}

PrefilterMethod parse_prefilter_method(const std::string& name) {
    if (name == "cone")
        return PrefilterMethod::cone;
    if (name == "importance")
        return PrefilterMethod::importance;
    fail("unknown prefilter {} (expected cone (Moschos algorithm 6) or importance)", quote(name));
}

const char* to_string(Shading shading) {
    return shading == Shading::moschos ? "moschos" : "split-sum";
}

Shading parse_shading(const std::string& name) {
    if (name == "moschos")
        return Shading::moschos;
    if (name == "split-sum")
        return Shading::split_sum;
    fail("unknown IBL shading {} (expected moschos (algorithms 7-8) or split-sum)", quote(name));
}

std::string PrefilterSettings::describe() const {
    if (method == PrefilterMethod::cone) {
        return fmt::format("cone samples={} seed={}", samples, seed);
    }
    return fmt::format("importance distribution={} samples={} min_face={} filtered={}",
                       to_string(distribution), samples, min_face_size, filtered);
}

}  // namespace sl::ibl
