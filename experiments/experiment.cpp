#include "experiments/experiment.h"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "experiments/sequence.h"
#include "frame/volume_method.h"
#include "methods/registry.h"
#include "scenes/scene_file.h"
#include "scenes/toml_reader.h"
#include "scenes/variations.h"

namespace sl::experiments {

namespace fs = std::filesystem;

namespace {

// Numbers as the shortest text that reads back to the same value ("0.1", "64").
std::string value_text(const toml::node& node) {
    if (const auto* i = node.as_integer()) {
        return std::to_string(i->get());
    }
    if (const auto* d = node.as_floating_point()) {
        return fmt::format("{}", d->get());
    }
    if (const auto* b = node.as_boolean()) {
        return b->get() ? "1" : "0";
    }
    if (const auto* s = node.as_string()) {
        return s->get();
    }
    return {};
}

bool is_scalar(const toml::node& node) {
    return node.is_number() || node.is_boolean() || node.is_string();
}

// A scalar or an array of scalars, as texts; a list sweeps.
std::vector<std::string> values(TomlTableReader& reader, std::string_view key) {
    const toml::node* node = reader.take(key);
    std::vector<std::string> texts;
    if (!node) {
        return texts;
    }
    if (is_scalar(*node)) {
        texts.push_back(value_text(*node));
    } else if (const toml::array* array = node->as_array()) {
        for (const toml::node& element : *array) {
            if (!is_scalar(element)) {
                reader.error(key, "expected a value or an array of values");
            }
            texts.push_back(value_text(element));
        }
        if (texts.empty()) {
            reader.error(key, "an empty list sweeps nothing");
        }
    } else {
        reader.error(key, "expected a value or an array of values");
    }
    return texts;
}

std::vector<std::string> strings(TomlTableReader& reader, std::string_view key) {
    if (const toml::node* node = reader.take(key)) {
        const toml::array* array = node->as_array();
        if (node->is_string() ||
            (array && std::all_of(array->begin(), array->end(),
                                  [](const toml::node& n) { return n.is_string(); }))) {
            return values(reader, key);
        }
        reader.error(key, "expected a string or an array of strings");
    }
    return {};
}

std::pair<int, int> parse_size_value(TomlTableReader& reader, std::string_view key,
                                     const std::string& text) {
    static const std::regex pattern(R"((\d{1,5})(?:x(\d{1,5}))?)");
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) {
        reader.error(key, fmt::format("{}: expected WIDTHxHEIGHT (or N for NxN)", quote(text)));
    }
    const int width = std::stoi(match[1]);
    const int height = match[2].matched ? std::stoi(match[2]) : width;
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        reader.error(key, fmt::format("{}: width and height must be in 1..16384", quote(text)));
    }
    return {width, height};
}

void assign(toml::table& table, const std::string& key, const toml::node& node) {
    node.visit([&](const auto& value) { table.insert_or_assign(key, value); });
}

// Sets `path` (dot-separated) in `root`, creating tables on the way.
void set_path(toml::table& root, const std::string& path, const toml::node& value,
              const std::string& origin) {
    toml::table* table = &root;
    size_t begin = 0;
    while (true) {
        const size_t dot = path.find('.', begin);
        const std::string key = path.substr(begin, dot == std::string::npos ? dot : dot - begin);
        if (key.empty()) {
            fail("{}: override {}: empty key in the path", origin, quote(path));
        }
        if (dot == std::string::npos) {
            assign(*table, key, value);
            return;
        }
        toml::node* next = table->get(key);
        if (!next) {
            next = table->insert_or_assign(key, toml::table{}).first->second.as_table();
        }
        if (!next->is_table()) {
            fail("{}: override {}: {} is not a table", origin, quote(path), quote(key));
        }
        table = next->as_table();
        begin = dot + 1;
    }
}

// VALUE in TOML syntax (1, 0.5, "x", [1, 2], true), or else taken as a bare string.
toml::table parse_override_value(const std::string& value) {
    try {
        toml::table parsed = toml::parse("value = " + value);
        if (parsed.size() == 1 && parsed.contains("value")) {
            return parsed;
        }
    } catch (const toml::parse_error&) {
    }
    toml::table parsed;
    parsed.insert("value", value);
    return parsed;
}

// A preset's table flattened into dotted paths ("sweep.sizes" and [presets.x.sweep] sizes alike).
void flatten(const toml::table& table, const std::string& prefix,
             std::vector<std::pair<std::string, const toml::node*>>& out) {
    for (const auto& [key, node] : table) {
        const std::string path =
            prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
        if (const toml::table* sub = node.as_table()) {
            flatten(*sub, path, out);
        } else {
            out.emplace_back(path, &node);
        }
    }
}

void check_method_parameter(const std::string& method, const std::string& name,
                            const std::vector<std::string>& texts, TomlTableReader& reader) {
    const auto instance = methods::create_volume_method(method);
    if (!instance->has_parameter(name)) {
        reader.error(name,
                     fmt::format("method {} has no parameter {}", quote(method), quote(name)));
    }
    for (const std::string& text : texts) {
        try {
            instance->set(name, text);
        } catch (const Error& e) {
            reader.error(name, e.what());
        }
    }
}

}  // namespace

std::optional<double> parse_number(const std::string& text) {
    double value = 0.0;
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (ec != std::errc() || ptr != end) {
        return std::nullopt;
    }
    return value;
}

bool same_value(const std::string& a, const std::string& b) {
    const auto x = parse_number(a), y = parse_number(b);
    return x && y ? *x == *y : a == b;
}

std::string Cell::size() const {
    return fmt::format("{}x{}", width, height);
}

std::string Cell::settings_text() const {
    std::string text;
    for (const Setting& s : settings) {
        text += (text.empty() ? "" : ";") + s.name + "=" + s.value;
    }
    return text;
}

std::string Cell::id() const {
    // A scene file is named by its file name: ids (and image names) do not depend on where the
    // experiment was run.
    const std::string label =
        scene.find('/') != std::string::npos ? std::filesystem::path(scene).stem().string() : scene;
    std::string id = fmt::format("{}.{}.{}", label, method, size());
    for (const Setting& s : settings) {
        id += "." + s.name + "=" + s.value;
    }
    for (char& c : id) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '=' && c != '-' &&
            c != '+' && c != '_') {
            c = '_';
        }
    }
    return id;
}

const std::string* Cell::setting(const std::string& name) const {
    for (const Setting& s : settings) {
        if (s.name == name) {
            return &s.value;
        }
    }
    return nullptr;
}

bool Experiment::excluded(const Cell& cell) const {
    for (const Exclusion& exclusion : exclusions) {
        bool all = true;
        for (const auto& [key, accepted] : exclusion.keys) {
            std::optional<std::string> value;
            if (key == "scene") {
                value = cell.scene;
            } else if (key == "method") {
                value = cell.method;
            } else if (key == "size") {
                value = cell.size();
            } else if (const std::string* setting = cell.setting(key)) {
                value = *setting;
            }
            all =
                all && value &&
                std::any_of(accepted.begin(), accepted.end(),
                            [&, is_size = key == "size"](const std::string& a) {
                                return same_value(*value, a) || (is_size && a + "x" + a == *value);
                            });
        }
        if (all) {
            return true;
        }
    }
    return false;
}

std::vector<Cell> Experiment::cells() const {
    std::vector<Cell> cells;
    for (const std::string& scene : scenes) {
        for (const auto& [width, height] : sizes) {
            for (const std::string& method : methods) {
                const auto instance = methods::create_volume_method(method);
                // The scene's variations, then the swept parameters this method declares; its own
                // lists replace global ones.
                std::vector<std::pair<std::string, std::vector<std::string>>> axes = scene_params;
                for (const auto& axis : params) {
                    if (instance->has_parameter(axis.first)) {
                        axes.push_back(axis);
                    }
                }
                if (auto own = method_params.find(method); own != method_params.end()) {
                    for (const auto& axis : own->second) {
                        auto same = std::find_if(axes.begin(), axes.end(), [&](const auto& a) {
                            return a.first == axis.first;
                        });
                        if (same != axes.end()) {
                            same->second = axis.second;
                        } else {
                            axes.push_back(axis);
                        }
                    }
                }
                // Cartesian product, the first axis varying slowest.
                std::vector<size_t> index(axes.size(), 0);
                while (true) {
                    Cell cell{scene, method, width, height, {}};
                    for (size_t a = 0; a < axes.size(); ++a) {
                        cell.settings.push_back({axes[a].first, axes[a].second[index[a]]});
                    }
                    std::sort(cell.settings.begin(), cell.settings.end(),
                              [](const Setting& x, const Setting& y) { return x.name < y.name; });
                    if (!excluded(cell)) {
                        cells.push_back(std::move(cell));
                    }
                    size_t a = axes.size();
                    while (a > 0 && ++index[a - 1] == axes[a - 1].second.size()) {
                        index[--a] = 0;
                    }
                    if (a == 0) {
                        break;
                    }
                }
            }
        }
    }
    return cells;
}

std::vector<std::string> Experiment::listed_values(const std::string& parameter) const {
    std::vector<std::string> listed;
    auto add = [&](const auto& axes) {
        for (const auto& [axis, texts] : axes) {
            for (const std::string& value : texts) {
                if (axis == parameter &&
                    std::none_of(listed.begin(), listed.end(),
                                 [&](const std::string& l) { return same_value(l, value); })) {
                    listed.push_back(value);
                }
            }
        }
    };
    add(scene_params);
    add(params);
    for (const auto& [method, axes] : method_params) {
        add(axes);
    }
    return listed;
}

fs::path Experiment::output_directory() const {
    std::string path = out;
    for (size_t at; (at = path.find("{name}")) != std::string::npos;) {
        path.replace(at, 6, name);
    }
    return path;
}

namespace {

// [protocol]: what a cell measures and how often (still or animation, frames, repetitions,
// isolation, order).
void read_protocol(const toml::table& table, const std::string& origin, Experiment& x) {
    TomlTableReader r(table, origin, "[protocol]");
    const std::string kind = r.string("kind", "still");
    if (kind != "still" && kind != "animation") {
        r.error("kind", fmt::format("{}: expected \"still\" (one frame measured again and "
                                    "again) or \"animation\" (the scene played frame by "
                                    "frame)",
                                    quote(kind)));
    }
    x.protocol.kind = kind == "animation" ? ProtocolKind::animation : ProtocolKind::still;
    const bool animated = x.protocol.animated();
    x.protocol.warmup = r.integer_in("warmup", x.protocol.warmup, 0, 1000);
    x.protocol.frames =
        r.integer_in("frames", animated ? 0 : x.protocol.frames, animated ? 0 : 1, 100000);
    if (animated) {
        x.protocol.step = r.number_in("step", 0.0, 0.0, 3600.0);
        x.protocol.orbit_degrees = r.number_in("orbit_degrees", 90.0, -3600.0, 3600.0);
        const std::string mode = r.string("frame_mode", "serial");
        if (mode != "serial" && mode != "pipelined") {
            r.error("frame_mode",
                    fmt::format("{}: expected \"serial\" or \"pipelined\"", quote(mode)));
        }
        x.protocol.pipelined = mode == "pipelined";
        if (r.has("paired")) {
            r.error("paired",
                    "only for kind = \"still\": an animation's frames are played through the "
                    "frame loop, one method at a time (compare two animation cells instead)");
        }
    } else {
        x.protocol.paired = r.boolean("paired", false);
        for (const char* key : {"step", "orbit_degrees", "frame_mode"}) {
            if (r.has(key)) {
                r.error(key, "only for kind = \"animation\"");
            }
        }
    }
    x.protocol.repetitions = r.integer_in("repetitions", x.protocol.repetitions, 1, 1000);
    const std::string isolation = r.string("isolation", "context");
    if (isolation != "context" && isolation != "process") {
        r.error("isolation", fmt::format("{}: expected \"context\" (a fresh GL context per "
                                         "repetition) or \"process\" (a fresh process)",
                                         quote(isolation)));
    }
    x.protocol.isolation = isolation == "process" ? Isolation::process : Isolation::context;
    const std::string order = r.string("order", "sweep");
    if (order != "sweep" && order != "shuffled") {
        r.error("order", fmt::format("{}: expected \"sweep\" or \"shuffled\"", quote(order)));
    }
    x.protocol.order_shuffled = order == "shuffled";
    x.protocol.seed = uint64_t(r.integer_in("seed", 1, 0, 1 << 30));
    r.finish();
}

// [render]: the frame's shadow map.
void read_render(const toml::table& table, const std::string& origin, Experiment& x) {
    TomlTableReader r(table, origin, "[render]");
    x.render.shadow = r.string("shadow", x.render.shadow);
    try {
        frame::parse_shadow_filter(x.render.shadow);
    } catch (const Error& e) {
        r.error("shadow", e.what());
    }
    x.render.shadow_map_size = r.integer_in("shadow_map_size", x.render.shadow_map_size, 16, 16384);
    x.render.pcf_radius = r.integer_in("pcf_radius", x.render.pcf_radius, 0, 8);
    r.finish();
}

// [sweep]: scenes, methods, sizes, [sweep.params] (global and per method) and [sweep.scene].
// Every scene of the sweep loads (and fits the protocol's animation), every method exists. A scene
// file named relative to the experiment file is found beside it first.
void check_scenes_and_methods(TomlTableReader& r, const std::string& origin, Experiment& x) {
    const fs::path folder = fs::path(origin).parent_path();
    for (std::string& scene : x.scenes) {
        std::error_code ec;
        if (scene.ends_with(".toml") && fs::path(scene).is_relative() && !folder.empty() &&
            fs::is_regular_file(folder / scene, ec)) {
            scene = (folder / scene).lexically_normal().string();
        }
        try {
            const Scene loaded = load_scene(scene, SceneSearchPaths::defaults());
            if (x.protocol.animated()) {
                Sequence{loaded, x.protocol};  // frames and step fit its animation
            }
        } catch (const Error& e) {
            r.error("scenes", e.what());
        }
    }
    for (const std::string& method : x.methods) {
        try {
            methods::create_volume_method(method);
        } catch (const Error& e) {
            r.error("methods", e.what());
        }
    }
}

// `[sweep.params.METHOD]`: parameters of one method, applied where the sweep has it.
void read_method_params(TomlTableReader& p, const std::string& origin, const std::string& method,
                        const toml::table& own, Experiment& x) {
    p.take(method);
    const auto known = methods::volume_method_names();
    if (std::find(known.begin(), known.end(), method) == known.end()) {
        p.error(method, fmt::format("a table of parameters must be named after a method (known: "
                                    "{})",
                                    fmt::join(known, ", ")));
    }
    if (std::find(x.methods.begin(), x.methods.end(), method) == x.methods.end()) {
        return;  // not swept (e.g. --set sweep.methods=...): not applied
    }
    TomlTableReader m(own, origin, "[sweep.params." + method + "]");
    for (const auto& [name_node, value] : own) {
        const std::string name(name_node.str());
        std::vector<std::string> texts = values(m, name);
        check_method_parameter(method, name, texts, m);
        x.method_params[method].emplace_back(name, std::move(texts));
    }
}

// `[sweep.params] KEY = [...]`: a parameter of every swept method that has it.
void read_shared_param(TomlTableReader& p, const std::string& origin, const std::string& key,
                       Experiment& x) {
    std::vector<std::string> texts = values(p, key);
    bool declared = false;
    for (const std::string& method : x.methods) {
        if (methods::create_volume_method(method)->has_parameter(key)) {
            check_method_parameter(method, key, texts, p);
            declared = true;
        }
    }
    if (declared) {
        x.params.emplace_back(key, std::move(texts));
        return;
    }
    // A parameter of no swept method is no error when some method has it (the sweep's methods
    // may have been overridden), but it takes no effect: said so. When no method has it, it is
    // a typo.
    std::vector<std::string> all;
    for (const std::string& m : methods::volume_method_names()) {
        const auto method = methods::create_volume_method(m);
        for (const frame::Parameter& parameter : method->parameters()) {
            all.push_back(parameter.name);
        }
    }
    if (std::find(all.begin(), all.end(), key) == all.end()) {
        p.error(key, fmt::format("no method has this parameter{} (see `shaftlab methods`)",
                                 did_you_mean(key, all)));
    }
    x.warnings.push_back(
        fmt::format("{}: [sweep.params] {}: no method of this sweep ({}) has it: not applied",
                    origin, key, fmt::join(x.methods, ", ")));
}

void read_sweep(TomlTableReader& top, const std::string& origin, Experiment& x) {
    const toml::table* sweep = top.table("sweep");
    if (!sweep) {
        top.error("sweep", "missing: an experiment needs [sweep] scenes, methods and sizes");
    }
    TomlTableReader r(*sweep, origin, "[sweep]");
    x.scenes = strings(r, "scenes");
    x.methods = strings(r, "methods");
    for (const auto& [key, list] :
         {std::pair{"scenes", &x.scenes}, std::pair{"methods", &x.methods}}) {
        if (list->empty()) {
            r.error(key, "missing: the sweep needs at least one");
        }
    }
    check_scenes_and_methods(r, origin, x);
    std::vector<std::string> sizes = values(r, "sizes");
    if (sizes.empty()) {
        r.error("sizes", "missing: the sweep needs at least one size, e.g. [\"256x256\"]");
    }
    for (const std::string& size : sizes) {
        x.sizes.push_back(parse_size_value(r, "sizes", size));
    }
    if (const toml::table* params = r.table("params")) {
        TomlTableReader p(*params, origin, "[sweep.params]");
        for (const auto& [key_node, node] : *params) {
            const std::string key(key_node.str());
            if (const toml::table* own = node.as_table()) {
                read_method_params(p, origin, key, *own, x);
            } else {
                read_shared_param(p, origin, key, x);
            }
        }
    }
    if (const toml::table* scene = r.table("scene")) {
        TomlTableReader v(*scene, origin, "[sweep.scene]");
        for (const auto& [key_node, node] : *scene) {
            const std::string key(key_node.str());
            std::vector<std::string> texts = values(v, key);
            for (const std::string& value : texts) {
                if (const std::string error = scene_variation_error(key, value); !error.empty()) {
                    v.error(key, error);
                }
            }
            x.scene_params.emplace_back(key, std::move(texts));
        }
    }
    r.finish();
}

// [[exclude]]: cells removed from the sweep.
void read_exclusions(TomlTableReader& top, const std::string& origin, Experiment& x) {
    if (const toml::array* exclusions = top.array("exclude")) {
        for (const toml::node& node : *exclusions) {
            const toml::table* table = node.as_table();
            if (!table) {
                top.error("exclude", "expected [[exclude]] tables");
            }
            TomlTableReader r(*table, origin, "[[exclude]]");
            Exclusion exclusion;
            for (const auto& [key_node, value] : *table) {
                const std::string key(key_node.str());
                const bool known =
                    key == "scene" || key == "method" || key == "size" || is_scene_variation(key) ||
                    std::any_of(x.methods.begin(), x.methods.end(), [&](const std::string& m) {
                        return methods::create_volume_method(m)->has_parameter(key);
                    });
                if (!known) {
                    r.error(key,
                            "not scene, method, size, a scene variation or a parameter of a method "
                            "of the sweep");
                }
                exclusion.keys[key] = values(r, key);
            }
            if (exclusion.keys.empty()) {
                top.error("exclude", "an empty [[exclude]] would exclude every cell");
            }
            x.exclusions.push_back(std::move(exclusion));
        }
    }
}

// [reference]: the method the images are scored against, the metrics and the animation scoring.
void read_reference(const toml::table& table, const std::string& origin, Experiment& x) {
    TomlTableReader r(table, origin, "[reference]");
    x.reference = r.string("method", x.reference);
    if (!x.reference.empty()) {
        try {
            methods::create_volume_method(x.reference);
        } catch (const Error& e) {
            r.error("method", e.what());
        }
    }
    for (const char* key : {"stride", "pop_factor", "pop_floor"}) {
        if (r.has(key) && !x.protocol.animated()) {
            r.error(key, "only for [protocol] kind = \"animation\"");
        }
    }
    x.scoring.stride = r.integer_in("stride", x.scoring.stride, 1, 100000);
    x.scoring.pop_factor = r.number_in("pop_factor", x.scoring.pop_factor, 1.01, 1e6);
    x.scoring.pop_floor = r.number_in("pop_floor", x.scoring.pop_floor, 0.0, 1.0);
    if (r.has("metrics")) {
        x.metrics = strings(r, "metrics");
        for (const std::string& metric : x.metrics) {
            if (metric != "rel_rmse" && metric != "max_abs" && metric != "psnr") {
                r.error("metrics",
                        fmt::format("unknown metric {} (rel_rmse, max_abs, psnr)", quote(metric)));
            }
        }
    }
    r.finish();
}

// [outputs]: images, previews, plots.
void read_outputs(const toml::table& table, const std::string& origin, Experiment& x) {
    TomlTableReader r(table, origin, "[outputs]");
    x.images = r.boolean("images", x.images);
    x.previews = r.boolean("previews", x.previews);
    x.preview_max_size = r.integer_in("preview_max_size", x.preview_max_size, 1, 16384);
    x.plots = r.boolean("plots", x.plots);
    r.finish();
}

// [table]: the rows of table.md and the metric beside each FPS.
void read_table(const toml::table& table, const std::string& origin, Experiment& x) {
    TomlTableReader r(table, origin, "[table]");
    if (r.has("rows")) {
        x.table_rows = strings(r, "rows");
        // A row dimension is the scene, the size or a parameter some method declares (the
        // sweep's methods may be overridden, as for [sweep.params]).
        const auto known = methods::volume_method_names();
        for (const std::string& row : x.table_rows) {
            if (row == "scene" || row == "size" || is_scene_variation(row) ||
                std::any_of(known.begin(), known.end(), [&](const std::string& m) {
                    return methods::create_volume_method(m)->has_parameter(row);
                })) {
                continue;
            }
            r.error("rows", fmt::format("unknown row {}: expected scene, size, a scene "
                                        "variation or a method's parameter (see `shaftlab "
                                        "methods`)",
                                        quote(row)));
        }
    }
    x.table_metric = r.string("metric", x.table_metric);
    if (x.reference.empty() ||
        std::find(x.metrics.begin(), x.metrics.end(), x.table_metric) == x.metrics.end()) {
        if (r.has("metric")) {
            r.error("metric", "not one of the [reference] metrics computed");
        }
        x.table_metric = x.reference.empty() || x.metrics.empty() ? "" : x.metrics.front();
    }
    r.finish();
}

// [equal_error]: targets, baselines, tolerance and the searches per method.
// One method's search: `[equal_error.search.METHOD]`, else dz or samples where the method has
// them; nullopt for a method measured as is (beamtree has no parameter to trade). The bounds
// must be numbers in the parameter's range.
std::optional<Search> read_search(const std::string& origin, const std::string& method,
                                  const toml::table* own) {
    const auto instance = methods::create_volume_method(method);
    Search search;
    if (own) {
        TomlTableReader s(*own, origin, "[equal_error.search." + method + "]");
        search.parameter = s.string("parameter");
        if (!instance->has_parameter(search.parameter)) {
            s.error("parameter", fmt::format("method '{}' has no parameter {}", method,
                                             quote(search.parameter)));
        }
        search.cheap = s.number("cheap");
        search.expensive = s.number("expensive");
        s.finish();
    } else if (instance->has_parameter("dz")) {
        search = {"dz", 1.0, 0.01};  // slab depth, metres
    } else if (instance->has_parameter("samples")) {
        search = {"samples", 4, 1024};  // march steps
    } else {
        return std::nullopt;
    }
    for (const frame::Parameter& p : instance->parameters()) {
        if (p.name != search.parameter) {
            continue;
        }
        if (p.type == frame::Parameter::Type::choice || p.type == frame::Parameter::Type::boolean) {
            fail("{}: [equal_error.search.{}]: '{}' is {}, not a number", origin, method, p.name,
                 p.type == frame::Parameter::Type::choice ? "a choice" : "a flag");
        }
        search.integer = p.type == frame::Parameter::Type::integer;
        auto inside = [&](double v) { return v >= p.min && v <= p.max; };
        if (!inside(search.cheap) || !inside(search.expensive) || !(search.cheap > 0.0) ||
            !(search.expensive > 0.0) || search.cheap == search.expensive) {
            fail(
                "{}: [equal_error.search.{}]: cheap and expensive must differ and lie in {}'s "
                "range [{}, {}]",
                origin, method, p.name, p.min, p.max);
        }
    }
    return search;
}

// Targets, baselines and the plain method of `[equal_error]`.
void read_equal_error_targets(TomlTableReader& r, const Experiment& x, EqualError& e) {
    for (const std::string& target : values(r, "targets")) {
        const auto value = parse_number(target);
        if (!value || !(*value > 0.0 && *value < 1.0)) {
            r.error("targets", fmt::format("{}: a relative RMSE in (0, 1)", quote(target)));
        }
        e.targets.push_back(*value);
    }
    if (e.targets.empty()) {
        r.error("targets", "missing: the relative RMSE to reach, e.g. [0.01]");
    }
    if (x.reference.empty()) {
        r.error("targets", "equal error needs a [reference] method");
    }
    auto in_sweep = [&](const std::string& method) {
        return std::find(x.methods.begin(), x.methods.end(), method) != x.methods.end();
    };
    e.baselines = strings(r, "baselines");
    for (const std::string& baseline : e.baselines) {
        if (!in_sweep(baseline)) {
            r.error("baselines", fmt::format("{} is not a method of the sweep", quote(baseline)));
        }
    }
    // The plain method: `plain`, or march where the sweep has it.
    e.plain = r.has("plain") ? r.string("plain") : in_sweep("march") ? "march" : "";
    if (!e.plain.empty() && !in_sweep(e.plain)) {
        r.error("plain", fmt::format("{} is not a method of the sweep", quote(e.plain)));
    }
}

void read_equal_error(TomlTableReader& top, const std::string& origin, Experiment& x) {
    const toml::table* table = top.table("equal_error");
    if (!table) {
        return;
    }
    TomlTableReader r(*table, origin, "[equal_error]");
    EqualError e;
    read_equal_error_targets(r, x, e);
    e.tolerance = r.number_in("tolerance", e.tolerance, 1e-3, 10.0);
    const toml::table* searches = r.table("search");
    for (const std::string& method : x.methods) {
        if (const std::optional<Search> search =
                read_search(origin, method, searches ? (*searches)[method].as_table() : nullptr)) {
            e.search[method] = *search;
        }
    }
    if (searches) {
        for (const auto& [key, node] : *searches) {
            if (!e.search.contains(std::string(key.str())) || !node.is_table()) {
                fail("{}: [equal_error.search]: {} is not a method of the sweep", origin,
                     quote(key.str()));
            }
        }
    }
    r.finish();
    x.equal_error = std::move(e);
}

}  // namespace

Experiment parse_experiment(const std::string& text, const std::string& origin,
                            const std::vector<std::string>& presets,
                            const std::vector<std::string>& overrides) {
    toml::table root;
    try {
        root = toml::parse(text, origin);
    } catch (const toml::parse_error& e) {
        fail("{}:{}: {}", origin, e.source().begin.line, e.description());
    }
    Experiment x;
    x.source = origin;
    x.text = text;

    // Presets, then --set overrides, into the document itself: they are read and validated
    // exactly like the file.
    const toml::table* preset_tables = root["presets"].as_table();
    for (const std::string& preset : presets) {
        const toml::table* table = preset_tables ? (*preset_tables)[preset].as_table() : nullptr;
        if (!table) {
            std::vector<std::string> known;
            if (preset_tables) {
                for (const auto& [key, node] : *preset_tables) {
                    known.emplace_back(key.str());
                }
            }
            fail("{}: unknown preset {} (presets: {})", origin, quote(preset),
                 known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", ")));
        }
        const toml::table copy = *table;  // set_path changes `root`, which holds `table`
        std::vector<std::pair<std::string, const toml::node*>> paths;
        flatten(copy, "", paths);
        for (const auto& [path, node] : paths) {
            if (path.starts_with("presets")) {
                fail("{}: preset {} may not set presets", origin, quote(preset));
            }
            set_path(root, path, *node, origin);
        }
        x.overrides.push_back("preset " + preset);
    }
    for (const std::string& override_text : overrides) {
        const size_t equals = override_text.find('=');
        if (equals == std::string::npos || equals == 0) {
            fail("--set {}: expected KEY.PATH=VALUE", quote(override_text));
        }
        const std::string path = override_text.substr(0, equals);
        const toml::table value = parse_override_value(override_text.substr(equals + 1));
        set_path(root, path, *value.get("value"), origin);
        x.overrides.push_back(override_text);
    }

    TomlTableReader top(root, origin, "");
    x.name = top.string("name");
    if (!std::regex_match(x.name, std::regex("[A-Za-z0-9_.-]+"))) {
        top.error("name", "use letters, digits, '_', '-' and '.' only (it names files)");
    }
    x.description = top.string("description", "");
    x.out = top.string("out", x.out);
    top.table("presets");  // applied above

    const toml::table empty;
    auto section = [&](std::string_view key) -> const toml::table& {
        const toml::table* table = top.table(key);
        return table ? *table : empty;
    };
    read_protocol(section("protocol"), origin, x);
    read_render(section("render"), origin, x);
    read_sweep(top, origin, x);
    read_exclusions(top, origin, x);
    read_reference(section("reference"), origin, x);
    read_outputs(section("outputs"), origin, x);
    read_table(section("table"), origin, x);
    read_equal_error(top, origin, x);
    top.finish();

    // The document as read (presets dropped: they are applied), for resuming and env.json.
    root.erase("presets");
    std::ostringstream effective;
    effective << root << "\n";
    x.effective = effective.str();
    return x;
}

Experiment load_experiment(const fs::path& path, const std::vector<std::string>& presets,
                           const std::vector<std::string>& overrides) {
    std::ifstream file(path, std::ios::binary);
    if (!file) {
        fail("{}: cannot read the experiment file", path.string());
    }
    std::ostringstream text;
    text << file.rdbuf();
    return parse_experiment(text.str(), path.string(), presets, overrides);
}

}  // namespace sl::experiments
