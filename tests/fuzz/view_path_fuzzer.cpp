// The viewer's scripted paths (viewer/view_path.h): any text parses or throws sl::Error, and a
// parsed path applies to a scene at every frame without a non-finite camera or light.
#include <cmath>

#include "scenes/scene.h"
#include "tests/fuzz/fuzz_support.h"
#include "viewer/view_path.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    return sl::fuzz::expect_load_or_error([&] {
        const sl::viewer::ViewPath path = sl::viewer::ViewPath::parse(text, "fuzz.toml");
        sl::Scene scene;
        for (int frame : {0, path.last_frame() / 2, path.last_frame(), path.last_frame() + 1}) {
            path.apply(frame, scene);
            for (float v : {scene.camera.position.x, scene.light.position.y,
                            scene.light.cone_half_angle_degrees}) {
                if (!std::isfinite(v)) {
                    std::abort();
                }
            }
        }
    });
}
