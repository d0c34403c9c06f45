#include <cstdio>

#include <fmt/format.h>

#include "app/commands.h"
#include "core/error.h"
#include "core/text.h"
#include "frame/volume_method.h"
#include "gl/platform.h"
#include "methods/registry.h"
#include "scenes/animation.h"
#include "scenes/scene_file.h"

namespace sl::app {

Command add_scenes_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand(
        "scenes",
        "List every scene that loads by name (objects, triangles, light, animation), or generate "
        "multiple:N or boxes:SEED");
    auto names_only = std::make_shared<bool>(false);
    auto generate = std::make_shared<std::string>();
    command->add_flag("--names", *names_only, "Print only the names, one per line");
    command->add_option("--generate", *generate,
                        "Print the TOML of a generated scene and exit: multiple:N (or N alone) "
                        "or boxes:SEED");
    return [=] {
        if (!generate->empty()) {
            const bool count_alone = generate->find_first_not_of("0123456789") == std::string::npos;
            const std::string name = count_alone ? "multiple:" + *generate : *generate;
            if (!is_generated_scene_name(name)) {
                fail("--generate {}: expected multiple:N, N or boxes:SEED", quote(*generate));
            }
            std::fputs(generated_scene_text(name).c_str(), stdout);
            return 0;
        }
        const SceneSearchPaths paths = SceneSearchPaths::defaults();
        for (const std::string& name : named_scene_names()) {
            if (*names_only) {
                fmt::print("{}\n", name);
                continue;
            }
            const Scene scene = load_scene(name, paths);
            const std::string motion =
                scene.animation
                    ? fmt::format("  animated {:g}-{:g} s at {:g} fps", scene.animation->start,
                                  scene.animation->end, scene.animation->fps)
                    : "";
            fmt::print(
                "{:<16} {:>3} objects {:>8} triangles  light cone {:.0f} deg  medium {}{}  "
                "{}\n",
                name, scene.objects.size(), scene.triangle_count(),
                scene.light.cone_half_angle_degrees, to_string(scene.medium.model), motion,
                scene.source.string());
        }
        if (!*names_only) {
            fmt::print("multiple:N  generated: N objects under one spot light\n");
            fmt::print(
                "boxes:SEED  generated: random boxes (their own bounding volumes) under a random "
                "spot light and medium, the eye inside the cone on odd seeds\n");
        }
        return 0;
    };
}

Command add_methods_command(CLI::App& app) {
    app.add_subcommand("methods", "List the volumetric methods and their parameters");
    return [] {
        for (const std::string& name : methods::volume_method_names()) {
            const auto method = methods::create_volume_method(name);
            fmt::print("{}\n  accepts: {}\n", name, method->accepts());
            for (const frame::Parameter& p : method->parameters()) {
                if (p.type == frame::Parameter::Type::choice) {
                    fmt::print("  {:<22} {:<8} default {:<8} one of {}  {}\n", p.name, "choice",
                               p.choices[size_t(p.default_value)], fmt::join(p.choices, "|"),
                               p.description);
                    continue;
                }
                fmt::print("  {:<22} {:<8} default {:<8} range [{}, {}]  {}\n", p.name,
                           p.type == frame::Parameter::Type::integer ? "integer" : "real",
                           p.default_value, p.min, p.max, p.description);
            }
        }
        return 0;
    };
}

Command add_gl_info_command(CLI::App& app) {
    CLI::App* command = app.add_subcommand("gl-info",
                                           "Print the headless OpenGL context shaftlab uses "
                                           "(SHAFTLAB_GL=osmesa|egl picks the backend)");
    (void)command;
    return [] {
        const auto platform = gl::create_headless_platform();
        const gl::ContextInfo info = platform->info();
        fmt::print("backend  {}\nvendor   {}\nrenderer {}\nversion  {}\nprofile  {}\n",
                   platform->backend(), info.vendor, info.renderer, info.version,
                   info.core_profile ? "core" : "compatibility");
        return 0;
    };
}

}  // namespace sl::app
