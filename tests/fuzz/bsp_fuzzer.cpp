// Quake 3 BSP maps (scenes/q3_bsp.h): any bytes parse into a checked map that converts to a
// model, or throw sl::Error.
#include <span>

#include "scenes/q3_bsp.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto bytes = std::as_bytes(std::span<const uint8_t>(data, size));
    return sl::fuzz::expect_load_or_error(
        [&] { sl::q3::to_model(sl::q3::parse(bytes, "input.bsp"), "input.bsp"); });
}
