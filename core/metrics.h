#pragma once
// Error of an image against a reference (DESIGN.md §6), on the I_s buffer:
//   rel_rmse = sqrt(Σ (a - r)² / Σ r²)          (0 when equal, 1 for an all-black image)
//   max_abs  = max |a - r| over pixels and channels
//   psnr     = 20 log10(max r / rmse) in dB, rmse = sqrt(mean (a - r)²); +inf when equal

#include "core/image.h"

namespace sl {

struct ErrorMetrics {
    double rel_rmse = 0.0;
    double max_abs = 0.0;
    double psnr = 0.0;
};

// Throws sl::Error when the sizes differ.
ErrorMetrics compare_images(const Image& image, const Image& reference);

}  // namespace sl
