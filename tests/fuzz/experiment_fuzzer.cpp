// Experiment files (experiments/experiment.h): any text parses into an experiment whose sweep
// expands, or throws sl::Error.
#include "experiments/experiment.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    return sl::fuzz::expect_load_or_error([&] {
        const sl::experiments::Experiment experiment =
            sl::experiments::parse_experiment(text, "fuzz.toml");
        experiment.cells();
    });
}
