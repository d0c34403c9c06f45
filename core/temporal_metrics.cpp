#include "core/temporal_metrics.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace sl {

void TemporalMetrics::add(const Image& image, const Image& reference) {
    if (image.width != reference.width || image.height != reference.height) {
        fail("temporal metrics: the image is {}x{}, its reference {}x{}", image.width, image.height,
             reference.width, reference.height);
    }
    if (frames_ > 0 && (image.width != width_ || image.height != height_)) {
        fail("temporal metrics: frame {} is {}x{}, the sequence {}x{}", frames_, image.width,
             image.height, width_, height_);
    }
    const size_t n = image.rgb.size();
    std::vector<float> error(n);
    double squares = 0.0;
    for (size_t i = 0; i < n; ++i) {
        const float a = image.rgb[i], r = reference.rgb[i];
        if (!std::isfinite(a) || !std::isfinite(r)) {
            const size_t pixel = i / 3;
            fail("temporal metrics: frame {}: {} is not finite at pixel ({}, {})", frames_,
                 std::isfinite(a) ? "the reference" : "the image", pixel % size_t(image.width),
                 pixel / size_t(image.width));
        }
        error[i] = a - r;
        squares += double(r) * double(r);
    }
    reference_squares_ += squares;
    values_ += double(n);
    if (frames_ >= 1) {
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i) {
            const double d = double(error[i]) - double(previous_[i]);
            sum += d * d;
        }
        first_squares_ += sum;
        first_values_ += double(n);
    }
    if (frames_ >= 2) {
        double sum = 0.0;
        for (size_t i = 0; i < n; ++i) {
            const double d =
                double(error[i]) - 2.0 * double(previous_[i]) + double(before_previous_[i]);
            sum += d * d;
        }
        second_squares_ += sum;
        second_values_ += double(n);
    }
    before_previous_ = std::move(previous_);
    previous_ = std::move(error);
    width_ = image.width;
    height_ = image.height;
    ++frames_;
}

double TemporalMetrics::temporal_error() const {
    if (first_values_ == 0.0 || reference_squares_ == 0.0) {
        return 0.0;
    }
    return std::sqrt(first_squares_ / first_values_) / std::sqrt(reference_squares_ / values_);
}

double TemporalMetrics::flicker() const {
    if (second_values_ == 0.0 || reference_squares_ == 0.0) {
        return 0.0;
    }
    return std::sqrt(second_squares_ / second_values_ / 6.0) /
           std::sqrt(reference_squares_ / values_);
}

int count_pops(const std::vector<double>& errors, double factor, double floor) {
    if (!(factor > 1.0) || !(floor >= 0.0)) {
        fail("popping: the factor must exceed 1 and the floor be at least 0 (got {}, {})", factor,
             floor);
    }
    if (errors.empty()) {
        return 0;
    }
    std::vector<double> sorted = errors;
    std::sort(sorted.begin(), sorted.end());
    const size_t m = sorted.size() / 2;
    const double median = sorted.size() % 2 ? sorted[m] : 0.5 * (sorted[m - 1] + sorted[m]);
    const double threshold = std::max(factor * median, median + floor);
    return int(
        std::count_if(errors.begin(), errors.end(), [&](double e) { return e > threshold; }));
}

}  // namespace sl
