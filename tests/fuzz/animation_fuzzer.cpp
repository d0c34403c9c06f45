// Animation tracks (scenes/animation.h; scene files' [animation] and the viewer's --path files):
// any text parses or throws sl::Error, and a parsed animation gives, at every frame time, a scene
// with a finite camera, light and object placements, or throws sl::Error (an overshoot).
#include <cmath>

#include "scenes/animation.h"
#include "scenes/scene.h"
#include "tests/fuzz/fuzz_support.h"

using sl::fuzz::finite;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    static const sl::Scene scene = [] {
        sl::Scene s;
        s.objects.resize(2);
        s.objects[0].name = "floor";
        s.objects[1].name = "box";
        return s;
    }();
    return sl::fuzz::expect_load_or_error([&] {
        const sl::Animation a = sl::parse_animation(text, "fuzz.toml", scene);
        const int frames = a.frame_count();
        for (int frame : {0, frames / 2, frames - 1}) {
            const sl::Scene s = sl::scene_at(scene, a, std::min(a.frame_time(frame), a.end));
            bool ok = finite(s.camera.position) && finite(s.light.position) &&
                      std::isfinite(s.light.cone_half_angle_degrees);
            for (const sl::Object& o : s.objects) {
                ok = ok && finite(o.placement.translate) && finite(o.placement.scale);
            }
            if (!ok) {
                std::abort();
            }
        }
    });
}
