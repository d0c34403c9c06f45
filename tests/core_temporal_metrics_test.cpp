// Temporal metrics (core/temporal_metrics.h) on synthetic sequences whose answers are known:
// a static image scores 0, added white noise of σ scores σ as flicker (and √2 σ as temporal
// error), an error that drifts smoothly is temporal error but not flicker, a constant bias is
// neither, and a one-frame pop counts once.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "core/temporal_metrics.h"

namespace sl::test {
namespace {

// A smooth, non-black reference that changes with t (a moving light's gradient).
Image reference_frame(int t, int width = 64, int height = 48) {
    Image image(width, height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            for (int c = 0; c < 3; ++c) {
                image.rgb[(size_t(y) * size_t(width) + size_t(x)) * 3 + size_t(c)] =
                    float(1.0 + 0.5 * std::sin(0.1 * x + 0.07 * y + 0.05 * t + c));
            }
        }
    }
    return image;
}

double rms(const Image& image) {
    double sum = 0.0;
    for (const float v : image.rgb) {
        sum += double(v) * double(v);
    }
    return std::sqrt(sum / double(image.rgb.size()));
}

TEST(TemporalMetrics, AnExactSequenceScoresZero) {
    TemporalMetrics m;
    for (int t = 0; t < 10; ++t) {
        m.add(reference_frame(t), reference_frame(t));
    }
    EXPECT_EQ(m.frames(), 10);
    EXPECT_EQ(m.temporal_error(), 0.0);
    EXPECT_EQ(m.flicker(), 0.0);
}

TEST(TemporalMetrics, AStaticImageWithAStaticErrorScoresZero) {
    // A still frame with a constant bias: wrong, but perfectly stable.
    TemporalMetrics m;
    const Image truth = reference_frame(0);
    Image biased = truth;
    for (float& v : biased.rgb) {
        v = 0.9f * v + 0.02f;
    }
    for (int t = 0; t < 8; ++t) {
        m.add(biased, truth);
    }
    EXPECT_NEAR(m.temporal_error(), 0.0, 1e-12);
    EXPECT_NEAR(m.flicker(), 0.0, 1e-12);
}

TEST(TemporalMetrics, WhiteNoiseOfSigmaScoresSigmaAsFlicker) {
    for (const double sigma : {0.003, 0.02, 0.1}) {
        std::mt19937 random(7);
        TemporalMetrics m;
        const double scale = rms(reference_frame(0));  // ≈ the sequence's RMS
        for (int t = 0; t < 40; ++t) {
            const Image truth = reference_frame(t);
            Image noisy = truth;
            std::normal_distribution<double> noise(0.0, sigma * scale);
            for (float& v : noisy.rgb) {
                v += float(noise(random));
            }
            m.add(noisy, truth);
        }
        EXPECT_NEAR(m.flicker() / sigma, 1.0, 0.03) << "sigma " << sigma;
        EXPECT_NEAR(m.temporal_error() / sigma, std::sqrt(2.0), 0.04) << "sigma " << sigma;
    }
}

TEST(TemporalMetrics, ASmoothDriftIsTemporalErrorButNotFlicker) {
    // The error grows linearly along the sequence: it changes every frame (temporal error) but
    // never reverses (no flicker).
    TemporalMetrics m;
    for (int t = 0; t < 20; ++t) {
        const Image truth = reference_frame(t);
        Image drifting = truth;
        for (size_t i = 0; i < drifting.rgb.size(); ++i) {
            drifting.rgb[i] += float(0.001 * t * (1.0 + double(i % 7)));
        }
        m.add(drifting, truth);
    }
    EXPECT_GT(m.temporal_error(), 1e-3);
    EXPECT_LT(m.flicker(), 1e-3 * m.temporal_error());
}

TEST(TemporalMetrics, MismatchedOrBrokenFramesAreRefused) {
    TemporalMetrics m;
    m.add(reference_frame(0), reference_frame(0));
    EXPECT_THROW(m.add(reference_frame(1, 32, 48), reference_frame(1, 32, 48)), Error);
    EXPECT_THROW(m.add(reference_frame(1), reference_frame(1, 64, 40)), Error);
    Image broken = reference_frame(1);
    broken.rgb[100] = std::nanf("");
    EXPECT_THROW(m.add(broken, reference_frame(1)), Error);
    EXPECT_EQ(m.frames(), 1) << "a refused frame is not counted";
}

TEST(Popping, AOneFramePopCountsOnce) {
    std::vector<double> errors(30, 0.01);
    for (size_t i = 0; i < errors.size(); ++i) {
        errors[i] += 0.0005 * double(i % 3);  // ordinary variation is no pop
    }
    EXPECT_EQ(count_pops(errors, 3.0, 0.002), 0);
    errors[17] = 0.05;
    EXPECT_EQ(count_pops(errors, 3.0, 0.002), 1);
    errors[4] = 0.08;
    EXPECT_EQ(count_pops(errors, 3.0, 0.002), 2);
    // An exact method's rounding: tripling a tiny median is not a pop below the floor.
    std::vector<double> exact(20, 1e-6);
    exact[3] = 5e-6;
    EXPECT_EQ(count_pops(exact, 3.0, 0.002), 0);
    EXPECT_EQ(count_pops({}, 3.0, 0.0), 0);
    EXPECT_THROW(count_pops(errors, 1.0, 0.0), Error);
}

}  // namespace
}  // namespace sl::test
