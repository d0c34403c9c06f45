#include "core/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace sl {

ErrorMetrics compare_images(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        fail("cannot compare a {}x{} image with a {}x{} reference", image.width, image.height,
             reference.width, reference.height);
    }
    double squared = 0.0, norm = 0.0, peak = 0.0;
    ErrorMetrics metrics;
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        const double a = image.rgb[i], r = reference.rgb[i];
        squared += (a - r) * (a - r);
        norm += r * r;
        peak = std::max(peak, r);
        metrics.max_abs = std::max(metrics.max_abs, std::abs(a - r));
    }
    metrics.rel_rmse = norm > 0.0 ? std::sqrt(squared / norm) : (squared > 0.0 ? 1.0 : 0.0);
    const double rmse = std::sqrt(squared / double(std::max<size_t>(1, image.rgb.size())));
    metrics.psnr =
        rmse > 0.0 ? 20.0 * std::log10(peak / rmse) : std::numeric_limits<double>::infinity();
    return metrics;
}

}  // namespace sl
