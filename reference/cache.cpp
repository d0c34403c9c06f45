#include "reference/cache.h"

#include <fmt/format.h>

#include "core/cache.h"
#include "core/error.h"

namespace sl::reference {

std::filesystem::path cache_file(const Scene& scene, int width, int height,
                                 const ReferenceOptions& options) {
    return cache_directory() /
           fmt::format("reference-{:016x}.exr", reference_key(scene, width, height, options));
}

std::optional<Image> find_cached(const Scene& scene, int width, int height,
                                 const ReferenceOptions& options) {
    const std::filesystem::path file = cache_file(scene, width, height, options);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
        return std::nullopt;
    }
    Image image = read_exr(file);
    require_finite(image, file.string());
    return image;
}

Image cached_reference(const Scene& scene, int width, int height, const ReferenceOptions& options,
                       const std::function<void(double)>& progress) {
    if (std::optional<Image> cached = find_cached(scene, width, height, options)) {
        return std::move(*cached);
    }
    const ReferenceRenderer renderer(scene);
    Image image = renderer.render(width, height, options, progress);
    require_finite(image, "reference I_s");
    write_cache_file(cache_file(scene, width, height, options),
                     [&](const std::filesystem::path& temporary) { write_exr(image, temporary); });
    return image;
}

}  // namespace sl::reference
