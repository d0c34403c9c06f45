// Images and result files: EXR round trip, the tone curve, all-or-nothing output.

#include <cmath>
#include <fstream>
#include <limits>

#include "core/error.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "tests/support.h"

namespace sl::test {
namespace {

// EXR stores 32-bit floats: what is written is read back bit for bit, HDR values included.
TEST(Image, ExrRoundTripIsExact) {
    Image image(7, 5);
    for (size_t i = 0; i < image.rgb.size(); ++i) {
        image.rgb[i] = float(i) * 0.37f + (i % 3 == 0 ? 1234.5f : 1e-6f);
    }
    TempDir dir;
    write_exr(image, dir / "a.exr");
    const Image back = read_exr(dir / "a.exr");
    EXPECT_EQ(back.width, 7);
    EXPECT_EQ(back.height, 5);
    EXPECT_EQ(back.rgb, image.rgb);
    EXPECT_THROW(read_exr(dir / "missing.exr"), Error);
}

// The preview curve: Reinhard after exposure, then sRGB: 0 -> 0, 1 -> 0.5 -> 188, monotonic.
TEST(Image, ToneMapIsReinhardThenSrgb) {
    Image image(4, 1);
    image.set(0, 0, glm::vec3(0.0f));
    image.set(1, 0, glm::vec3(1.0f));
    image.set(2, 0, glm::vec3(1e6f));
    image.set(3, 0, glm::vec3(-1.0f));
    const std::vector<unsigned char> out = tone_map_srgb8(image, ToneMap{1.0f});
    EXPECT_EQ(out[0], 0);
    EXPECT_EQ(out[3], 188);  // sRGB(0.5) = 0.7354
    EXPECT_EQ(out[6], 255);
    EXPECT_EQ(out[9], 0);
    EXPECT_EQ(tone_map_srgb8(image, ToneMap{2.0f})[3], 213);  // 2/3 -> 0.8360
    unsigned char previous = 0;
    for (float x = 0.0f; x < 50.0f; x += 0.01f) {
        Image pixel(1, 1);
        pixel.set(0, 0, glm::vec3(x));
        const unsigned char v = tone_map_srgb8(pixel, ToneMap{})[0];
        EXPECT_GE(v, previous);
        previous = v;
    }
}

// A PNG is written with its signature; sizes that do not match the pixels are refused.
TEST(Image, PngIsWritten) {
    TempDir dir;
    write_png(Image(3, 2), ToneMap{}, dir / "a.png");
    std::ifstream in(dir / "a.png", std::ios::binary);
    char signature[8] = {};
    in.read(signature, 8);
    EXPECT_EQ(std::string(signature + 1, 3), "PNG");
    EXPECT_THROW(write_png(std::vector<unsigned char>(5), 3, 2, dir / "b.png"), Error);
}

// The error metrics on known images: equal images score 0 and +inf dB; a black image scores
// Per label: the relative RMSE over that label's pixels alone, and the last entry over every
// The signed difference picture: red where the image is brighter, blue where darker, the largest
// difference at full scale, equal pixels black.
TEST(ErrorMetrics, SignedDifferenceMapShowsTheSignAtSquareRootScale) {
    Image reference(3, 1), image(3, 1);
    reference.rgb = {1, 1, 1, 1, 1, 1, 1, 1, 1};
    image.rgb = {1, 1, 1, 2, 2, 2, 1, 1, 0.25f};
    double full = 0.0;
    const std::vector<unsigned char> rgb = signed_difference_map(image, reference, full);
    EXPECT_DOUBLE_EQ(full, 3.0);
    EXPECT_EQ(rgb, (std::vector<unsigned char>{0, 0, 0, 255, 0, 0, 0, 0, 128}));
    EXPECT_THROW(signed_difference_map(Image(2, 1), reference, full), Error);
}

// labelled pixel; unlabelled pixels count nowhere.
TEST(ErrorMetrics, LabelledRelativeRmseScoresEachLabelOnItsOwnPixels) {
    Image reference(3, 1), image(3, 1);
    for (float& v : reference.rgb) {
        v = 1.0f;
    }
    image.rgb = {1.0f, 1.0f, 1.0f, 2.0f, 2.0f, 2.0f, 9.0f, 9.0f, 9.0f};
    const std::vector<double> errors = labelled_rel_rmse(image, reference, {0, 1, -1}, 2);
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_DOUBLE_EQ(errors[0], 0.0);
    EXPECT_DOUBLE_EQ(errors[1], 1.0);
    EXPECT_DOUBLE_EQ(errors[2], std::sqrt(0.5));
    EXPECT_THROW(labelled_rel_rmse(image, reference, {0, 1}, 2), Error);
}

// rel_rmse 1; a uniform offset gives its closed-form PSNR; sizes must match.
TEST(ErrorMetrics, KnownValues) {
    Image reference(4, 2);
    for (size_t i = 0; i < reference.rgb.size(); ++i) {
        reference.rgb[i] = 0.5f + 0.1f * float(i % 5);
    }
    const ErrorMetrics same = compare_images(reference, reference);
    EXPECT_EQ(same.rel_rmse, 0.0);
    EXPECT_EQ(same.max_abs, 0.0);
    EXPECT_TRUE(std::isinf(same.psnr));
    EXPECT_NEAR(compare_images(Image(4, 2), reference).rel_rmse, 1.0, 1e-12);
    Image offset = reference;
    for (float& v : offset.rgb)
        v += 0.01f;
    const ErrorMetrics shifted = compare_images(offset, reference);
    EXPECT_NEAR(shifted.max_abs, 0.01, 1e-6);
    EXPECT_NEAR(shifted.psnr, 20.0 * std::log10(0.9 / 0.01), 1e-3);  // peak 0.9, rmse 0.01
    EXPECT_THROW(compare_images(Image(3, 2), reference), Error);
}

// Result files appear together on commit, or not at all when any step fails.
TEST(OutputFiles, AllOrNothing) {
    TempDir dir;
    {
        OutputFiles files(dir.path());
        files.add_text("a.txt", "a");
        files.add_text("b.txt", "b");
        EXPECT_EQ(files.commit().size(), 2u);
    }
    EXPECT_EQ(dir.file_count(), 2u);

    TempDir failed;
    try {
        OutputFiles files(failed.path());
        files.add_text("a.txt", "a");
        files.add("b.txt", [](const std::filesystem::path&) { fail("simulated failure"); });
        files.commit();
        ADD_FAILURE() << "the failure was swallowed";
    } catch (const Error&) {
    }
    EXPECT_EQ(failed.file_count(), 0u) << "temporaries must be removed";

    // The folders a failed set made are removed with it; a committed set keeps its own.
    TempDir root;
    try {
        OutputFiles files(root / "new" / "deeper");
        files.add_text("a.txt", "a");
        fail("simulated failure");
    } catch (const Error&) {
    }
    EXPECT_FALSE(std::filesystem::exists(root / "new")) << "the made folders must go too";
    {
        OutputFiles files(root / "kept");
        files.add_text("a.txt", "a");
        files.commit();
    }
    EXPECT_TRUE(std::filesystem::exists(root / "kept" / "a.txt"));
}

// No output holds a NaN or an infinity: write_exr names the file and the first bad pixel and
// writes nothing; require_finite names the buffer it is given.
TEST(Image, NonFiniteOutputsAreRefusedNamingThePixel) {
    TempDir dir;
    Image image(6, 3);
    image.set(4, 1, {0.0f, 0.0f, std::numeric_limits<float>::infinity()});
    try {
        write_exr(image, dir / "out.exr");
        ADD_FAILURE() << "an infinite pixel was written";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("out.exr: pixel (4, 1) channel 2 is inf"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out.exr"));
    image.set(4, 1, {0.0f, 0.0f, 0.0f});
    image.set(0, 2, {std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f});
    EXPECT_THROW(require_finite(image, "I_s"), Error);
    try {
        require_finite(image, "I_s");
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "I_s: pixel (0, 2) channel 0 is nan: outputs must be finite");
    }
    EXPECT_THROW(Image(1 << 15, 2), Error) << "wider than kMaxImageSide";
}

}  // namespace
}  // namespace sl::test
