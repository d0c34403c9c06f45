#pragma once
// The on-disk cache of reference images: one EXR per reference_key() under $SHAFTLAB_CACHE
// (default ~/.cache/shaftlab), written to a temporary file and renamed, so that concurrent runs
// and interrupted ones never leave a half-written image behind. Shared by the `reference`
// method, the harness and the viewer's error view.

#include <filesystem>
#include <functional>
#include <optional>

#include "core/cache.h"
#include "core/image.h"
#include "reference/reference.h"
#include "scenes/scene.h"

namespace sl::reference {

std::filesystem::path cache_file(const Scene& scene, int width, int height,
                                 const ReferenceOptions& options);
// The cached image for exactly this scene, view, size and options, if one exists.
std::optional<Image> find_cached(const Scene& scene, int width, int height,
                                 const ReferenceOptions& options);
// The cached image, or the reference computed now (`progress` receives the fraction done) and
// cached. A failure to write the cache only costs the next run the time again.
Image cached_reference(const Scene& scene, int width, int height, const ReferenceOptions& options,
                       const std::function<void(double)>& progress = {});

}  // namespace sl::reference
