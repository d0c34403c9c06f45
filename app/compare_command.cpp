// `shaftlab compare A.exr B.exr`: the error metrics of A against B, and optionally a signed
// difference picture (red where A is above B, blue where below, scaled to the largest
// difference).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "app/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/output_files.h"

namespace sl::app {

namespace {

struct CompareArguments {
    std::string image;
    std::string reference;
    std::string difference;  // PNG path, optional
};

int run_compare(const CompareArguments& args) {
    if (!args.difference.empty()) {
        std::error_code ec;
        const std::filesystem::path path(args.difference);
        if (!path.has_filename() || std::filesystem::is_directory(path, ec)) {
            fail("--difference {}: a directory; expected the path of the PNG file to write",
                 quote(args.difference));
        }
    }
    const Image image = read_exr(args.image), reference = read_exr(args.reference);
    // A NaN would score as a perfect or a meaningless match: name the file and the pixel.
    require_finite(image, args.image);
    require_finite(reference, args.reference);
    const ErrorMetrics error = compare_images(image, reference);
    fmt::print("rel_rmse {:.6g}  max_abs {:.6g}  psnr {:.2f} dB\n", error.rel_rmse, error.max_abs,
               error.psnr);
    if (args.difference.empty())
        return 0;
    double largest = 0.0;
    const std::vector<unsigned char> rgb = signed_difference_map(image, reference, largest);
    const std::filesystem::path path(args.difference);
    OutputFiles outputs(path.parent_path().empty() ? "." : path.parent_path());
    outputs.add(path.filename().string(), [&](const std::filesystem::path& staged) {
        write_png(rgb, image.width, image.height, staged);
    });
    outputs.commit();
    fmt::print("difference (sqrt scale, full = {:.4g}): {}\n", largest, args.difference);
    return 0;
}

}  // namespace

Command add_compare_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "compare", "Error metrics of one EXR against another (rel_rmse, max_abs, psnr)");
    auto args = std::make_shared<CompareArguments>();
    command->add_option("image", args->image, "EXR to score")->required()->check(CLI::ExistingFile);
    command->add_option("reference", args->reference, "EXR to score against")
        ->required()
        ->check(CLI::ExistingFile);
    command->add_option("--difference", args->difference,
                        "Write a signed difference PNG (red: image above, blue: below)");
    return [args] { return run_compare(*args); };
}

}  // namespace sl::app
