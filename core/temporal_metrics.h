#pragma once
// Temporal stability of an image sequence against its reference sequence (docs/design.md §11,
// docs/harness.md "Temporal metrics"). With e_t = I_t − R_t the error image of frame t (per pixel
// and channel), mean_p the mean over pixels and channels, and RMS(R) = sqrt(mean_{t,p} R_t²) over
// the sequence:
//
//   temporal error  TE = sqrt( mean_{t≥1} mean_p (e_t − e_{t−1})² ) / RMS(R)
//                   how much the error changes from frame to frame, whatever its cause; the
//                   reference's own change cancels, so an exact method scores 0.
//   flicker         F  = sqrt( mean_{t≥2} mean_p (e_t − 2 e_{t−1} + e_{t−2})² / 6 ) / RMS(R)
//                   the second difference of I_s with the reference's own taken out: the part of
//                   the error that reverses from one frame to the next. An error that drifts
//                   smoothly along the animation (a plane method's banding sliding with the
//                   light) scores 0; white noise of standard deviation σ·RMS(R), independent
//                   per frame, scores σ (its second difference has variance 6σ²; its first,
//                   2σ², so TE = √2 σ).
//   popping         the number of frames whose relative RMSE exceeds k × the sequence's median
//                   and the median plus a floor (the floor keeps an exact method's rounding from
//                   counting): a one-frame jump counts once.
//
// The frames added are the scored ones (a harness stride k scores every k-th frame; the
// differences are then between scored frames).

#include <vector>

#include "core/image.h"

namespace sl {

class TemporalMetrics {
public:
    // The next frame and its reference; throws sl::Error when the size differs from the first
    // frame's or either holds a NaN or an infinity.
    void add(const Image& image, const Image& reference);

    int frames() const { return frames_; }
    // 0 until the sequence has 2 (temporal error) or 3 (flicker) frames, or when the reference
    // is black.
    double temporal_error() const;
    double flicker() const;

private:
    int frames_ = 0;
    int width_ = 0, height_ = 0;
    std::vector<float> previous_, before_previous_;  // e_{t−1}, e_{t−2}
    double reference_squares_ = 0.0;                 // Σ_{t,p} R²
    double values_ = 0.0;                            // Σ_t (pixels · channels)
    double first_squares_ = 0.0, first_values_ = 0.0;
    double second_squares_ = 0.0, second_values_ = 0.0;
};

// Frames whose error exceeds factor × median(errors) and median + floor (the popping count
// above); factor > 1, floor >= 0.
int count_pops(const std::vector<double>& errors, double factor, double floor);

}  // namespace sl
