#pragma once
// Experiment files (TOML, docs/design.md §6): a cartesian sweep of scenes × methods × sizes ×
// method parameters with exclusions, a measuring protocol, the reference the images are scored
// against, the outputs to write and, optionally, an equal-error search. Every key is read in
// experiment.cpp next to its validation; an unknown key is an error naming the file and key.
//
//   name = "nilsson_table61"          out = "out/{name}"  (the default output directory; the
//                                     committed runs are written to results/NAME with --out)
//   description = "..."
//   [protocol]    kind = "still" | "animation", warmup = 2, frames = 10, repetitions = 1,
//                 isolation = "context" | "process", order = "sweep" | "shuffled", seed = 1 (of
//                 the shuffle); for kind = "animation" (docs/design.md §11): frames = 0 (the whole
//                 animation; 120 for an orbit), step = 0 (seconds per frame; 0: 1/fps of the
//                 scene's [animation]), orbit_degrees = 90 (a scene without [animation]: the
//                 camera circles its target this far over the frames), frame_mode = "serial" |
//                 "pipelined" (frame/frame_loop.h); for kind = "still": paired = false (true:
//                 each frame paired with a frame of `none`, docs/harness.md "Paired")
//   [render]      shadow = "hard" | "pcf" | "vsm", shadow_map_size = 2048, pcf_radius = 1
//   [sweep]       scenes = [...], methods = [...], sizes = ["256x256", ...]   (scene files
//                 relative to the experiment file are found beside it first)
//   [sweep.params]          dz = [0.5, 0.1], jitter = 0      (a list sweeps, a scalar is fixed;
//                           applied to every method that declares the parameter)
//   [sweep.params.march]    samples = [16, 64]               (for one method only)
//   [sweep.scene]           sss_grid = ["30x29", "40x39"], camera_distance = [0.55, 1]
//                           (variations of every scene, scenes/variations.h; swept for every
//                           method, named in cells, tables and exclusions like parameters)
//   [[exclude]]   method = "hybrid1", size = ["1024x1024"]   (a cell matching every key is
//                 skipped; keys: scene, method, size, any parameter; values or lists of values)
//   [reference]   method = "reference" (or "" for none), metrics = ["rel_rmse", "max_abs", "psnr"],
//                 animation cells: stride = 1 (every k-th frame scored), pop_factor = 3,
//                 pop_floor = 0.002 (core/temporal_metrics.h)
//   [outputs]     images = true (I_s EXR per cell), previews = true (PNG), plots = true,
//                 preview_max_size = 512 (no PNG for larger cells: committed runs stay small)
//   [table]       rows = ["dz", "scene", "size"], metric = "rel_rmse"
//   [equal_error] targets = [0.01], baselines = ["planes", "march"], tolerance = 0.05
//   [equal_error.search.planes]  parameter = "dz", cheap = 1.0, expensive = 0.01
//   [presets.quick]  "sweep.sizes" = ["64x64"], "protocol.frames" = 2   (--preset quick)
//
// Overrides (`--preset NAME`, then `--set key.path=VALUE`, VALUE in TOML syntax or a bare
// string) are applied to the document before it is read, so they are validated like the file.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sl::experiments {

enum class Isolation { context, process };
enum class ProtocolKind { still, animation };

struct Protocol {
    ProtocolKind kind = ProtocolKind::still;
    int warmup = 2;       // frames drawn before measuring (shader compilation, first use)
    int frames = 10;      // measured frames per repetition (animation: frames played, 0: all)
    int repetitions = 1;  // fresh GL context (or process) per repetition
    Isolation isolation = Isolation::context;
    // The order cells run in: as swept, or shuffled (seeded) so that slow drifts of the machine
    // (thermal, other load) do not line up with one method or size.
    bool order_shuffled = false;
    uint64_t seed = 1;
    // Animation cells: the time step (0: 1/fps of the scene's [animation]), the orbit of a scene
    // without one, and whether frame k+1's CPU update runs beside frame k's draw.
    double step = 0.0;
    double orbit_degrees = 90.0;
    bool pipelined = false;
    // Still cells: each frame of a method measured in a pair with a frame of `none` at the
    // method's shadow map, in the same context (methods/frame_measurement.h), for a volume cost
    // by difference that cancels drift.
    bool paired = false;
    bool animated() const { return kind == ProtocolKind::animation; }
};

// Scoring an animation against the reference sequence (core/temporal_metrics.h).
struct AnimationScoring {
    int stride = 1;  // every stride-th frame (0, k, 2k, ...) is scored
    double pop_factor = 3.0;
    double pop_floor = 0.002;
};

struct RenderSettings {
    std::string shadow = "pcf";
    int shadow_map_size = 2048;
    int pcf_radius = 1;
};

// One method parameter setting, as text (numbers as written, choices by name).
struct Setting {
    std::string name;
    std::string value;
    bool operator==(const Setting&) const = default;
};

struct Cell {
    std::string scene;
    std::string method;
    int width = 0;
    int height = 0;
    std::vector<Setting> settings;  // sorted by name

    std::string size() const;           // "WxH"
    std::string settings_text() const;  // "dz=0.1;shadow=vsm"
    std::string id() const;             // file-name safe, unique within an experiment
    const std::string* setting(const std::string& name) const;  // null when not set
    bool operator==(const Cell&) const = default;
};

// The equal-error search over one parameter of a method: the value between `cheap` and
// `expensive` (log-spaced bisection; integers rounded) that is cheapest while its error is at or
// below the target.
struct Search {
    std::string parameter;
    double cheap = 0.0;
    double expensive = 0.0;
    bool integer = false;
};

struct EqualError {
    std::vector<double> targets;           // relative RMSE of I_s
    std::vector<std::string> baselines;    // the methods without regions the others face
    std::string plain;                     // the plain method every headline also faces
    double tolerance = 0.05;               // stop when expensive/cheap is within 1 + tolerance
    std::map<std::string, Search> search;  // per method; methods without one are measured as is
};

struct Exclusion {
    std::map<std::string, std::vector<std::string>> keys;  // scene, method, size, parameters
};

struct Experiment {
    std::string name;
    std::string description;
    std::filesystem::path source;
    std::string text;                    // the file, verbatim
    std::vector<std::string> overrides;  // presets and --set, in order applied
    std::string effective;               // the document after overrides, as TOML
    std::string out = "out/{name}";
    // Settings that take no effect in this sweep but are no error (a parameter of no swept
    // method, once --set changed the methods): `bench` prints them before it runs.
    std::vector<std::string> warnings;

    Protocol protocol;
    RenderSettings render;
    std::vector<std::string> scenes;
    std::vector<std::string> methods;
    std::vector<std::pair<int, int>> sizes;
    // Parameter → values for every method that declares it, and per method.
    std::vector<std::pair<std::string, std::vector<std::string>>> params;
    std::map<std::string, std::vector<std::pair<std::string, std::vector<std::string>>>>
        method_params;
    // Scene variation → values (scenes/variations.h), swept for every method.
    std::vector<std::pair<std::string, std::vector<std::string>>> scene_params;
    std::vector<Exclusion> exclusions;

    std::string reference = "reference";  // empty: no error metrics
    std::vector<std::string> metrics = {"rel_rmse", "max_abs", "psnr"};
    AnimationScoring scoring;
    bool images = true;
    bool previews = true;
    int preview_max_size = 16384;  // no PNG for cells wider or taller than this
    bool plots = true;
    std::vector<std::string> table_rows = {"dz", "scene", "size"};
    std::string table_metric = "rel_rmse";
    std::optional<EqualError> equal_error;

    // The sweep expanded: scenes × methods × sizes × every swept parameter the method declares,
    // exclusions removed, in a stable order (scene, size, method, parameters as listed).
    std::vector<Cell> cells() const;
    bool excluded(const Cell& cell) const;
    // The values listed for a parameter (globally or for a method), in the file's order.
    std::vector<std::string> listed_values(const std::string& parameter) const;
    // The output directory: `out` with {name} replaced.
    std::filesystem::path output_directory() const;
};

// Setting values as numbers when they are numbers: parse_number("0.10") = 0.1, nullopt for
// "vsm"; same_value compares as numbers when both are ("0.10" = "0.1"), else as text.
std::optional<double> parse_number(const std::string& text);
bool same_value(const std::string& a, const std::string& b);

// Reads an experiment file, applies the named presets and then the `key.path=VALUE` overrides.
// Throws sl::Error naming the file and key on any bad input (unknown keys, methods, parameters or
// values, empty sweeps).
Experiment load_experiment(const std::filesystem::path& path,
                           const std::vector<std::string>& presets = {},
                           const std::vector<std::string>& overrides = {});
Experiment parse_experiment(const std::string& text, const std::string& origin,
                            const std::vector<std::string>& presets = {},
                            const std::vector<std::string>& overrides = {});

}  // namespace sl::experiments
