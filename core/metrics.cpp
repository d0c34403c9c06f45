#include "core/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace sl {

ErrorMetrics compare_images(const Image& image, const Image& reference,
                            const std::vector<uint8_t>* scored) {
    if (image.width != reference.width || image.height != reference.height) {
        fail("cannot compare a {}x{} image with a {}x{} reference", image.width, image.height,
             reference.width, reference.height);
    }
    const size_t pixels = size_t(image.width) * size_t(image.height);
    if (scored && scored->size() != pixels) {
        fail("the scored-pixel mask holds {} pixels for a {}x{} image", scored->size(), image.width,
             image.height);
    }
    require_finite(image, "compared image");
    require_finite(reference, "reference");
    double squared = 0.0, norm = 0.0, peak = 0.0;
    size_t counted = 0;
    ErrorMetrics metrics;
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        if (scored && !(*scored)[i / 3]) {
            continue;
        }
        const double a = image.rgb[i], r = reference.rgb[i];
        squared += (a - r) * (a - r);
        norm += r * r;
        peak = std::max(peak, r);
        metrics.max_abs = std::max(metrics.max_abs, std::abs(a - r));
        ++counted;
    }
    metrics.rel_rmse = norm > 0.0 ? std::sqrt(squared / norm) : (squared > 0.0 ? 1.0 : 0.0);
    const double rmse = std::sqrt(squared / double(std::max<size_t>(1, counted)));
    metrics.psnr =
        rmse > 0.0 ? 20.0 * std::log10(peak / rmse) : std::numeric_limits<double>::infinity();
    metrics.unscored = pixels > 0 ? 1.0 - double(counted / 3) / double(pixels) : 0.0;
    return metrics;
}

glm::vec3 heat_color(double t) {
    // Five stops of matplotlib's inferno, linear in between.
    static constexpr float stops[5][3] = {{0.0f, 0.0f, 0.015f},
                                          {0.34f, 0.06f, 0.43f},
                                          {0.73f, 0.21f, 0.33f},
                                          {0.98f, 0.55f, 0.04f},
                                          {0.99f, 1.0f, 0.64f}};
    const double x = std::clamp(t, 0.0, 1.0) * 4.0;
    const int i = std::min(int(x), 3);
    const float f = float(x - i);
    return glm::vec3(stops[i][0], stops[i][1], stops[i][2]) * (1.0f - f) +
           glm::vec3(stops[i + 1][0], stops[i + 1][1], stops[i + 1][2]) * f;
}

std::vector<unsigned char> error_heat_map(const Image& image, const Image& reference,
                                          double full_scale) {
    if (image.width != reference.width || image.height != reference.height) {
        fail("error heat map: image is {}x{}, reference {}x{}", image.width, image.height,
             reference.width, reference.height);
    }
    if (!(full_scale > 0.0)) {
        fail("error heat map: full scale must be positive");
    }
    double sum_squares = 0.0;
    for (const float v : reference.rgb) {
        sum_squares += double(v) * v;
    }
    const size_t pixels = size_t(image.width) * image.height;
    const double rms = std::sqrt(sum_squares / double(std::max<size_t>(pixels, 1)));
    const double scale = rms > 0.0 ? 1.0 / (rms * full_scale) : 0.0;
    std::vector<unsigned char> rgb(pixels * 3);
    for (size_t p = 0; p < pixels; ++p) {
        double d2 = 0.0;
        for (int c = 0; c < 3; ++c) {
            const double d = double(image.rgb[p * 3 + c]) - reference.rgb[p * 3 + c];
            d2 += d * d;
        }
        // A non-finite pixel is an error at full scale, never hidden.
        const double t = std::isfinite(d2) ? std::sqrt(d2) * scale : 1.0;
        const glm::vec3 color = heat_color(rms > 0.0 ? t : (d2 > 0.0 ? 1.0 : 0.0));
        for (int c = 0; c < 3; ++c) {
            rgb[p * 3 + c] = static_cast<unsigned char>(std::lround(255.0f * color[c]));
        }
    }
    return rgb;
}

std::vector<double> labelled_rel_rmse(const Image& image, const Image& reference,
                                      const std::vector<int>& labels, int label_count) {
    if (image.width != reference.width || image.height != reference.height ||
        labels.size() != size_t(image.width) * size_t(image.height)) {
        fail("labelled_rel_rmse: {}x{} image, {}x{} reference and {} labels differ in size",
             image.width, image.height, reference.width, reference.height, labels.size());
    }
    std::vector<double> error(size_t(label_count) + 1, 0.0), norm(size_t(label_count) + 1, 0.0);
    for (size_t i = 0; i < labels.size(); ++i) {
        if (labels[i] < 0 || labels[i] >= label_count) {
            continue;
        }
        double e = 0.0, r = 0.0;
        for (size_t c = 0; c < 3; ++c) {
            const double d = double(image.rgb[3 * i + c]) - double(reference.rgb[3 * i + c]);
            e += d * d;
            r += double(reference.rgb[3 * i + c]) * double(reference.rgb[3 * i + c]);
        }
        for (const size_t k : {size_t(labels[i]), size_t(label_count)}) {
            error[k] += e;
            norm[k] += r;
        }
    }
    std::vector<double> result(error.size(), 0.0);
    for (size_t k = 0; k < result.size(); ++k) {
        result[k] = norm[k] > 0.0 ? std::sqrt(error[k] / norm[k]) : 0.0;
    }
    return result;
}

std::vector<unsigned char> signed_difference_map(const Image& image, const Image& reference,
                                                 double& full_scale) {
    if (image.width != reference.width || image.height != reference.height) {
        fail("difference of a {}x{} image and a {}x{} reference", image.width, image.height,
             reference.width, reference.height);
    }
    // Luminance-like sum of channels; the scale is the largest |difference|.
    std::vector<double> delta(size_t(image.width) * image.height);
    full_scale = 0.0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3 a = image.at(x, y), b = reference.at(x, y);
            const double d = double(a.r + a.g + a.b) - double(b.r + b.g + b.b);
            delta[size_t(y) * image.width + x] = d;
            full_scale = std::max(full_scale, std::abs(d));
        }
    }
    std::vector<unsigned char> rgb(delta.size() * 3, 0);
    for (size_t i = 0; i < delta.size(); ++i) {
        const double v = full_scale > 0.0 ? delta[i] / full_scale : 0.0;
        const auto level = static_cast<unsigned char>(std::lround(255.0 * std::sqrt(std::abs(v))));
        rgb[i * 3 + (v > 0.0 ? 0 : 2)] = level;
    }
    return rgb;
}

}  // namespace sl
