// Environment maps (ibl/environment.h): any EXR is read and checked (2:1, finite, non-negative,
// a finite range) and converted to a small cube map with its SH9, or throws sl::Error.
#include "ibl/cube_map.h"
#include "ibl/environment.h"
#include "ibl/sh9.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = sl::fuzz::write_input(data, size, ".exr");
    return sl::fuzz::expect_load_or_error([&] {
        const sl::Image image = sl::ibl::load_equirect(path);
        const sl::ibl::CubeMap cube = sl::ibl::cube_from_equirect(image, 8, 0.0f);
        sl::ibl::project_sh9(cube);
    });
}
