// OBJ models through assimp (scenes/model.h, load_mesh's path for every format but OFF): any file
// loads into a valid mesh or throws sl::Error, within the limits of scenes/mesh.h.
#include "scenes/mesh.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::filesystem::path path = sl::fuzz::write_input(data, size, ".obj");
    return sl::fuzz::expect_load_or_error([&] { sl::load_mesh(path); });
}
