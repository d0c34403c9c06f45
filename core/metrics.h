#pragma once
// Error of an image against a reference (docs/design.md §6), on the I_s buffer:
//   rel_rmse = sqrt(Σ (a - r)² / Σ r²)          (0 when equal, 1 for an all-black image)
//   max_abs  = max |a - r| over pixels and channels
//   psnr     = 20 log10(max r / rmse) in dB, rmse = sqrt(mean (a - r)²); +inf when equal

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace sl {

struct ErrorMetrics {
    double rel_rmse = 0.0;
    double max_abs = 0.0;
    double psnr = 0.0;
    double unscored = 0.0;  // the share of pixels left out (compare_images' `scored`)
};

// Throws sl::Error when the sizes differ, or when either holds a NaN or an infinity (named with
// its first such pixel): a score of a broken image would look like a result. With `scored` (one
// byte per pixel, rows top to bottom), only the pixels marked non-zero count, in every metric.
ErrorMetrics compare_images(const Image& image, const Image& reference,
                            const std::vector<uint8_t>* scored = nullptr);

// Relative RMSE sqrt(Σ |a − r|² / Σ |r|²) over the pixels of each label (labels[i] of pixel i in
// 0 .. label_count − 1; negative: no label), and, as the last entry, over every labelled pixel;
// 0 where a label has no reference energy. How `shaftlab ibl reference` scores each object.
// Throws sl::Error when the sizes differ.
std::vector<double> labelled_rel_rmse(const Image& image, const Image& reference,
                                      const std::vector<int>& labels, int label_count);

// Per-pixel error |a - r| (the RGB difference's length) relative to the reference's RMS pixel
// value sqrt(mean |r|²) — the pixel-level counterpart of rel_rmse — as an 8-bit RGB heat map,
// rows top to bottom: 0 black, through purple, red and orange, to pale yellow at `full_scale`
// and above (an inferno-like ramp). Throws sl::Error when the sizes differ or full_scale <= 0.
std::vector<unsigned char> error_heat_map(const Image& image, const Image& reference,
                                          double full_scale);
// The signed difference of two images as an 8-bit RGB picture, rows top to bottom: per pixel
// d = (sum of a's channels) − (sum of r's), red where positive and blue where negative, at
// 255·sqrt(|d| / full) with `full` the largest |d| (returned in `full_scale`; all black when the
// images are equal). Throws sl::Error when the sizes differ.
std::vector<unsigned char> signed_difference_map(const Image& image, const Image& reference,
                                                 double& full_scale);
// The ramp itself, t in [0, 1] (clamped).
glm::vec3 heat_color(double t);

}  // namespace sl
