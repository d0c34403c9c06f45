#include "viewer/viewer.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <thread>
#include <tuple>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "beamtree/beam_tree.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "core/image.h"
#include "core/metrics.h"
#include "core/output_files.h"
#include "experiments/measure.h"
#include "gl/debug.h"
#include "gl/platform.h"
#include "gl/renderer.h"
#include "gl/shaders.h"
#include "reference/cache.h"
#include "scenes/scene_file.h"
#include "viewer/camera_controller.h"
#include "viewer/region_overlay.h"
#include "viewer/saved_view.h"
#include "viewer/texture_preview.h"
#include "viewer/view_path.h"

namespace sl::viewer {

const std::vector<std::string>& layer_names() {
    static const std::vector<std::string> names = {"volumes", "outlines",  "light-view",
                                                   "error",   "previewer", "timings"};
    return names;
}

namespace {

using gl::GL;
using Clock = std::chrono::steady_clock;
using experiments::ms_since;

constexpr size_t kHistory = 240;  // frames in the timing graphs
constexpr int kLightViewSize = 256;

// A ring of the last kHistory values, oldest first when read with offset().
struct History {
    std::vector<float> values = std::vector<float>(kHistory, 0.0f);
    size_t next = 0;
    void push(double v) {
        values[next] = float(v);
        next = (next + 1) % kHistory;
    }
    float latest() const { return values[(next + kHistory - 1) % kHistory]; }
    float max() const { return *std::max_element(values.begin(), values.end()); }
};

// The CPU reference for the current view, computed on a thread of its own and cached on disk.
struct ReferenceJob {
    std::thread thread;
    std::atomic<double> progress{0.0};
    std::atomic<bool> done{false};
    std::string error;
};

class Viewer {
public:
    explicit Viewer(const ViewerOptions& options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;
    int run();

private:
    bool scripted() const { return options_.frames > 0; }
    void switch_method(const std::string& name);
    void scene_changed();  // light or medium: the beam tree and the method's prepare
    void prepare_method();
    void handle_input(double dt);
    void draw_frame();
    void update_error_view();
    void draw_ui();
    void ui_view();
    void ui_light();
    void ui_medium();
    void ui_environment();
    void ui_method();
    void ui_regions();
    void ui_error();
    void ui_save();
    void ui_timings();
    void ui_previewer();
    void ui_light_view();
    gl::TextureViews all_textures() const;
    void screenshot(const std::string& path);
    void write_in_scattering(const std::string& path);
    bool layer(const char* name) const;

    ViewerOptions options_;
    std::unique_ptr<gl::WindowPlatform> platform_;
    Scene scene_;
    CameraController controller_;
    CameraMode mode_ = CameraMode::orbit;
    std::optional<ViewPath> path_;  // scripted mode
    float fly_speed_ = 2.0f;        // metres per second
    std::unique_ptr<gl::VolumeMethod> method_;
    std::unique_ptr<gl::SceneRenderer> renderer_;
    int width_ = 0, height_ = 0;
    RegionOverlay overlay_;
    OverlaySettings overlay_settings_;
    std::map<std::string, bool> layers_;
    TexturePreview preview_;
    PreviewSettings preview_settings_;
    std::string preview_name_;
    std::string fitted_name_;  // the buffer whose range the previewer last fitted
    gl::Program blit_program_;
    gl::VertexArray empty_array_;

    // The last light and medium the beam tree and the method accepted.
    SpotLight good_light_;
    Medium good_medium_;
    std::string status_;               // the last error, shown in red
    Environment environment_pending_;  // baked settings being edited in the panel
    bool environment_editing_ = false;

    // Regions and timings.
    size_t beams_ = 0;
    std::array<size_t, 3> region_faces_{};
    std::array<double, 3> region_volume_{};
    double influence_volume_ = 0.0;
    double tree_ms_ = 0.0, extract_ms_ = 0.0, prepare_ms_ = 0.0;
    gl::FrameTimings timings_;
    gl::MethodStatistics statistics_;
    History frame_history_, cpu_history_, shadow_history_, surface_history_, volume_history_,
        composite_history_;
    Clock::time_point last_frame_ = Clock::now();

    // Error view.
    reference::ReferenceOptions reference_options_{};
    uint64_t reference_key_ = 0;
    std::optional<Image> reference_;
    std::unique_ptr<ReferenceJob> job_;
    gl::Texture heat_map_;
    float heat_scale_ = 0.5f;
    ErrorMetrics error_{};

    std::string save_path_;
    std::string saved_message_;
    bool take_screenshot_ = false;
    int frame_ = 0;
};

Viewer::Viewer(const ViewerOptions& options)
    : options_(options),
      scene_(load_scene(options.scene, SceneSearchPaths::defaults())),
      controller_(scene_.camera) {
    for (const std::string& name : layer_names()) {
        layers_[name] = false;
    }
    for (const std::string& name : options.layers) {
        if (!layers_.contains(name)) {
            std::string known;
            for (const std::string& n : layer_names())
                known += (known.empty() ? "" : ", ") + n;
            fail("unknown layer '{}' (known: {})", name, known);
        }
        layers_[name] = true;
    }
    overlay_settings_.volumes = layers_["volumes"];
    overlay_settings_.outlines = layers_["outlines"];
    // Fail on an unknown method, setting or path before opening a window.
    method_ = experiments::create_configured_method(options.method, options.shadow,
                                                    experiments::parse_settings(options.settings));
    if (!options.path.empty()) {
        path_ = ViewPath::load(options.path);
    }
    if (options.width < 16 || options.height < 16 || options.width > 8192 ||
        options.height > 8192) {
        fail("window size {}x{} must be in 16..8192", options.width, options.height);
    }
    save_path_ = options.save_experiment.empty()
                     ? fmt::format("experiments/view-{}-{}.toml", scene_.name, method_->name())
                     : options.save_experiment;
    if (!(options.error_scale > 0.0f)) {
        fail("--error-scale {} must be positive", options.error_scale);
    }
    heat_scale_ = options.error_scale;
    preview_name_ = options.preview.empty() ? "frame/in-scattering I_s" : options.preview;
    good_light_ = scene_.light;
    good_medium_ = scene_.medium;

    platform_ =
        gl::create_glfw_platform(options.width, options.height,
                                 fmt::format("shaftlab view: {}", scene_.name), !options.hidden);
    glfwSwapInterval(scripted() ? 0 : 1);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // the layout is the code's, not a file's
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(static_cast<GLFWwindow*>(platform_->native_window()), true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    blit_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "viewer/shaders/blit.frag"}});
    empty_array_ = gl::create_vertex_array();
    scene_changed();
    if (!status_.empty()) {
        fail("{}", status_);
    }
}

Viewer::~Viewer() {
    if (job_) {
        if (job_->done) {
            job_->thread.join();
        } else {
            std::fprintf(stderr, "shaftlab view: leaving the reference computation unfinished\n");
            job_->thread.detach();
            job_.release();  // the thread still uses it; the process is ending
        }
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
}

bool Viewer::layer(const char* name) const {
    return layers_.at(name);
}

void Viewer::switch_method(const std::string& name) {
    try {
        auto method = experiments::create_configured_method(name, options_.shadow, {});
        const auto start = Clock::now();
        method->prepare(scene_);
        prepare_ms_ = ms_since(start);
        method_ = std::move(method);
        status_.clear();
    } catch (const Error& e) {
        status_ = e.what();  // the previous method stays
    }
}

void Viewer::prepare_method() {
    try {
        const auto start = Clock::now();
        method_->prepare(scene_);
        prepare_ms_ = ms_since(start);
    } catch (const Error& e) {
        status_ = e.what();
    }
}

void Viewer::scene_changed() {
    try {
        auto start = Clock::now();
        const bt::BeamTree tree = bt::build_scene_beam_tree(scene_);
        tree_ms_ = ms_since(start);
        start = Clock::now();
        const bt::Regions regions = bt::extract_regions(tree);
        extract_ms_ = ms_since(start);
        overlay_.upload(regions, scene_.light.far);
        beams_ = regions.beam_count;
        for (int r = 0; r < 3; ++r) {
            region_faces_[size_t(r)] = regions.face_count(bt::Region(r));
        }
        region_volume_ = regions.volume;
        influence_volume_ = regions.influence_volume;
        start = Clock::now();
        method_->prepare(scene_);
        prepare_ms_ = ms_since(start);
        good_light_ = scene_.light;
        good_medium_ = scene_.medium;
        status_.clear();
    } catch (const Error& e) {
        // A light inside a bounding volume, a medium the method has no closed form for: say
        // so, and go back to the last state that worked.
        if (scripted()) {
            throw;
        }
        status_ = e.what();
        scene_.light = good_light_;
        scene_.medium = good_medium_;
        method_->prepare(scene_);
    }
}

void Viewer::handle_input(double dt) {
    const ImGuiIO& io = ImGui::GetIO();
    // The camera is written only when it moves: an untouched view keeps the scene's exact
    // camera (and with it the cache key of its reference).
    bool moved = false;
    auto* window = static_cast<GLFWwindow*>(platform_->native_window());
    if (!io.WantCaptureKeyboard) {
        if (ImGui::IsKeyPressed(GLFW_KEY_TAB, false)) {
            mode_ = mode_ == CameraMode::orbit ? CameraMode::fly : CameraMode::orbit;
        }
        if (ImGui::IsKeyPressed(GLFW_KEY_F1, false))
            options_.ui = !options_.ui;
        if (ImGui::IsKeyPressed(GLFW_KEY_F12, false))
            take_screenshot_ = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_V, false))
            overlay_settings_.volumes = !overlay_settings_.volumes;
        if (ImGui::IsKeyPressed(GLFW_KEY_O, false))
            overlay_settings_.outlines = !overlay_settings_.outlines;
        auto down = [&](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0f : 0.0f; };
        const glm::vec3 move(down(GLFW_KEY_D) - down(GLFW_KEY_A),
                             down(GLFW_KEY_E) - down(GLFW_KEY_Q),
                             down(GLFW_KEY_W) - down(GLFW_KEY_S));
        if (move != glm::vec3(0.0f)) {
            const float boost = io.KeyShift ? 4.0f : 1.0f;
            controller_.move(move * float(fly_speed_ * boost * dt));
            moved = true;
        }
    }
    if (!io.WantCaptureMouse) {
        const glm::vec2 d(io.MouseDelta.x, io.MouseDelta.y);
        constexpr float kTurn = 0.005f;  // radians per pixel
        if (io.KeyCtrl && (io.MouseDown[0] || io.MouseDown[1])) {
            // Drag the light's position (left) or target (right) in the camera's view plane.
            glm::vec3& point = io.MouseDown[0] ? scene_.light.position : scene_.light.target;
            const float distance = glm::length(point - scene_.camera.position);
            const float per_pixel = 2.0f * distance *
                                    std::tan(glm::radians(scene_.camera.fov_y_degrees) / 2.0f) /
                                    float(std::max(height_, 1));
            if (d != glm::vec2(0.0f)) {
                point += per_pixel * (d.x * controller_.right() - d.y * controller_.up());
                scene_changed();
            }
        } else if (mode_ == CameraMode::orbit) {
            const bool dragged = d != glm::vec2(0.0f);
            if (io.MouseDown[0] && dragged) {
                controller_.orbit(-d.x * kTurn, -d.y * kTurn);
                moved = true;
            }
            if ((io.MouseDown[1] || io.MouseDown[2]) && dragged) {
                const float pan = controller_.distance() * 0.0015f;
                controller_.move({-d.x * pan, d.y * pan, 0.0f});
                moved = true;
            }
            if (io.MouseWheel != 0.0f) {
                controller_.zoom(std::pow(0.9f, io.MouseWheel));
                moved = true;
            }
        } else {
            if ((io.MouseDown[1] || io.MouseDown[0]) && d != glm::vec2(0.0f)) {
                controller_.look(-d.x * kTurn, -d.y * kTurn);
                moved = true;
            }
            if (io.MouseWheel != 0.0f)
                fly_speed_ = std::clamp(fly_speed_ * std::pow(1.25f, io.MouseWheel), 0.05f, 200.0f);
        }
    }
    if (moved) {
        controller_.apply(scene_.camera);
    }
}

void Viewer::update_error_view() {
    if (job_ && job_->done) {
        job_->thread.join();
        if (!job_->error.empty())
            status_ = "reference: " + job_->error;
        job_.reset();
        reference_key_ = 0;  // look again: it is in the cache now
    }
    const uint64_t key = reference::reference_key(scene_, width_, height_, reference_options_);
    if (key != reference_key_) {
        reference_key_ = key;
        reference_ = reference::find_cached(scene_, width_, height_, reference_options_);
    }
    if (!reference_) {
        return;
    }
    const Image image = renderer_->read_in_scattering();
    error_ = compare_images(image, *reference_);
    const std::vector<unsigned char> rgb = error_heat_map(image, *reference_, heat_scale_);
    std::vector<unsigned char> flipped(rgb.size());
    const size_t row = size_t(width_) * 3;
    for (int y = 0; y < height_; ++y) {  // GL rows run bottom to top
        std::copy_n(&rgb[size_t(height_ - 1 - y) * row], row, &flipped[size_t(y) * row]);
    }
    if (!heat_map_ || texture_info(heat_map_.id()).width != width_ ||
        texture_info(heat_map_.id()).height != height_) {
        heat_map_ = gl::create_texture_2d(GL_RGBA8, width_, height_, GL_NEAREST);
        heat_map_.label("error heat map");
    }
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    GL.TextureSubImage2D(heat_map_.id(), 0, 0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE,
                         flipped.data());
}

gl::TextureViews Viewer::all_textures() const {
    gl::TextureViews views = renderer_->textures();
    for (gl::TextureView& view : method_->textures())
        views.push_back(std::move(view));
    if (overlay_settings_.volumes && overlay_.thickness())
        views.push_back({"viewer/region lengths (lit, uncertain, unlit)", overlay_.thickness()});
    if (layer("light-view") && overlay_.light_view())
        views.push_back({"viewer/light view of the leaves", overlay_.light_view()});
    if (heat_map_)
        views.push_back({"viewer/error heat map", heat_map_.id()});
    return views;
}

void Viewer::draw_frame() {
    int w = 0, h = 0;
    platform_->framebuffer_size(w, h);
    if (w <= 0 || h <= 0) {
        return;  // minimised
    }
    // An environment edited in the panel (file, size, rotation, prefilter) needs its chain baked
    // (or read from the cache) again; intensity, skybox and shading are uniforms.
    const bool rebake =
        renderer_ && !ibl::same_bake(renderer_->environment().source(), scene_.environment);
    if (!renderer_ || rebake || w != width_ || h != height_) {
        renderer_.reset();
        renderer_ = std::make_unique<gl::SceneRenderer>(
            scene_, gl::RenderOptions{.width = w, .height = h, .shadow = options_.shadow});
        width_ = w;
        height_ = h;
    }
    timings_ = renderer_->draw(*method_);
    frame_history_.push(ms_since(last_frame_));
    last_frame_ = Clock::now();
    cpu_history_.push(timings_.cpu_ms);
    shadow_history_.push(timings_.gpu.shadow_ms);
    surface_history_.push(timings_.gpu.surface_ms);
    volume_history_.push(timings_.gpu.volume_ms);
    composite_history_.push(timings_.gpu.composite_ms);
    if (layer("timings") || scripted()) {
        statistics_ = method_->statistics();
    }

    GLuint shown = 0;
    GLuint depth = 0;
    for (const gl::TextureView& view : renderer_->textures()) {
        if (view.name == "frame/display")
            shown = view.texture;
        if (view.name == "frame/surface depth")
            depth = view.texture;
    }
    if (layer("error")) {
        update_error_view();
        if (reference_)
            shown = heat_map_.id();
    }
    GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
    GL.Viewport(0, 0, w, h);
    GL.Disable(GL_BLEND);
    GL.Disable(GL_DEPTH_TEST);
    GL.UseProgram(blit_program_.id());
    GL.BindTextureUnit(0, shown);
    GL.BindVertexArray(empty_array_.id());
    GL.DrawArrays(GL_TRIANGLES, 0, 3);
    if (overlay_settings_.volumes || overlay_settings_.outlines) {
        overlay_.draw(0, depth, w, h, renderer_->uniforms().view_projection, overlay_settings_);
    }
    if (layer("light-view")) {
        overlay_.draw_light_view(scene_.light.projection() * scene_.light.view(), kLightViewSize);
    }
    gl::check_errors("drawing the viewer's frame");
}

void Viewer::screenshot(const std::string& path) {
    std::vector<unsigned char> rgb(size_t(width_) * height_ * 3);
    GL.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    GL.ReadBuffer(GL_BACK);
    GL.PixelStorei(GL_PACK_ALIGNMENT, 1);
    GL.ReadPixels(0, 0, width_, height_, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    gl::check_errors("reading the window back");
    std::vector<unsigned char> flipped(rgb.size());
    const size_t row = size_t(width_) * 3;
    for (int y = 0; y < height_; ++y) {
        std::copy_n(&rgb[size_t(height_ - 1 - y) * row], row, &flipped[size_t(y) * row]);
    }
    const std::filesystem::path file = std::filesystem::absolute(path);
    OutputFiles outputs(file.parent_path());
    outputs.add(file.filename().string(), [&](const std::filesystem::path& temporary) {
        write_png(flipped, width_, height_, temporary);
    });
    outputs.commit();
    saved_message_ = "screenshot: " + file.string();
    std::printf("shaftlab view: %s\n", saved_message_.c_str());
}

void Viewer::write_in_scattering(const std::string& path) {
    const Image image = renderer_->read_in_scattering();
    const std::filesystem::path file = std::filesystem::absolute(path);
    OutputFiles outputs(file.parent_path());
    outputs.add(file.filename().string(),
                [&](const std::filesystem::path& temporary) { write_exr(image, temporary); });
    outputs.commit();
}

int Viewer::run() {
    const float orbit_step = options_.frames > 1
                                 ? glm::radians(options_.orbit_degrees) / float(options_.frames - 1)
                                 : 0.0f;
    while (!platform_->should_close()) {
        platform_->poll_events();
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        const double dt = std::min(ImGui::GetIO().DeltaTime, 0.1f);
        if (scripted()) {
            if (path_) {
                const SpotLight before = scene_.light;
                path_->apply(frame_, scene_);
                controller_ = CameraController(scene_.camera);
                if (before.position != scene_.light.position ||
                    before.target != scene_.light.target ||
                    before.cone_half_angle_degrees != scene_.light.cone_half_angle_degrees) {
                    scene_changed();
                }
            }
            if (frame_ > 0 && orbit_step != 0.0f) {
                controller_.orbit(orbit_step, 0.0f);
                controller_.apply(scene_.camera);
            }
        } else {
            handle_input(dt);
        }
        draw_frame();
        if (options_.ui) {
            draw_ui();
        }
        ImGui::Render();
        GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
        GL.Viewport(0, 0, width_, height_);
        ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
        gl::check_errors("drawing the user interface");

        const bool last = scripted() && frame_ + 1 >= options_.frames;
        if (take_screenshot_) {
            take_screenshot_ = false;
            screenshot(
                fmt::format("shaftlab-{}-{}-{:04}.png", scene_.name, method_->name(), frame_));
        }
        if (last) {
            if (!options_.screenshot.empty())
                screenshot(options_.screenshot);
            if (!options_.in_scattering.empty())
                write_in_scattering(options_.in_scattering);
            if (!options_.save_experiment.empty()) {
                const SavedView saved =
                    save_view_as_experiment(options_.save_experiment, scene_, options_.scene,
                                            *method_, width_, height_, options_.shadow);
                std::printf("shaftlab view: saved %s and %s\n", saved.experiment.c_str(),
                            saved.scene.c_str());
            }
            double gpu = timings_.gpu.total_ms();
            std::printf(
                "shaftlab view: %d frames of %s with %s at %dx%d; last frame %.2f ms GPU, %.2f ms "
                "CPU; beam tree %zu beams, %.2f ms\n",
                options_.frames, scene_.name.c_str(), method_->name().c_str(), width_, height_, gpu,
                timings_.cpu_ms, beams_, tree_ms_);
            if (layer("error")) {
                if (reference_) {
                    std::printf(
                        "shaftlab view: error against the cached reference: rel_rmse %.4g\n",
                        error_.rel_rmse);
                } else {
                    std::printf("shaftlab view: no cached reference for this view\n");
                }
            }
        }
        platform_->swap_buffers();
        ++frame_;
        if (last) {
            break;
        }
    }
    return 0;
}

// ---- the user interface -------------------------------------------------------------------

void help_marker(const std::string& text) {
    if (!text.empty() && ImGui::IsItemHovered()) {
        ImGui::SetTooltip("%s", text.c_str());
    }
}

void Viewer::draw_ui() {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, float(std::max(height_ - 16, 200))),
                             ImGuiCond_FirstUseEver);
    ImGui::Begin("shaftlab");
    ImGui::Text("%s: %zu objects, %zu triangles", scene_.name.c_str(), scene_.objects.size(),
                scene_.triangle_count());
    ImGui::Text("%.1f fps (%.1f ms) at %dx%d", 1000.0 / std::max(frame_history_.latest(), 1e-3f),
                frame_history_.latest(), width_, height_);
    if (!status_.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.35f, 0.3f, 1.0f));
        ImGui::TextWrapped("%s", status_.c_str());
        ImGui::PopStyleColor();
    }
    if (ImGui::CollapsingHeader("Method", ImGuiTreeNodeFlags_DefaultOpen))
        ui_method();
    if (ImGui::CollapsingHeader("Regions", ImGuiTreeNodeFlags_DefaultOpen))
        ui_regions();
    if (ImGui::CollapsingHeader("Camera"))
        ui_view();
    if (ImGui::CollapsingHeader("Light", ImGuiTreeNodeFlags_DefaultOpen))
        ui_light();
    if (ImGui::CollapsingHeader("Medium"))
        ui_medium();
    if (ImGui::CollapsingHeader("Environment (IBL)"))
        ui_environment();
    if (ImGui::CollapsingHeader("Error view"))
        ui_error();
    if (ImGui::CollapsingHeader("Save"))
        ui_save();
    ImGui::Separator();
    for (const char* name : {"timings", "previewer", "light-view"}) {
        ImGui::Checkbox(name, &layers_[name]);
        ImGui::SameLine();
    }
    ImGui::NewLine();
    ImGui::TextDisabled("F1 panels  F12 screenshot  Tab orbit/fly  V/O layers");
    ImGui::End();
    if (layer("timings"))
        ui_timings();
    if (layer("previewer"))
        ui_previewer();
    if (layer("light-view"))
        ui_light_view();
}

void Viewer::ui_method() {
    const std::string current = method_->name();
    if (ImGui::BeginCombo("method", current.c_str())) {
        for (const std::string& name : methods::volume_method_names()) {
            if (ImGui::Selectable(name.c_str(), name == current) && name != current) {
                switch_method(name);
            }
        }
        ImGui::EndCombo();
    }
    const std::vector<gl::Parameter> parameters = method_->parameters();
    for (const gl::Parameter& p : parameters) {
        std::optional<std::string> text;
        bool commit = false;
        switch (p.type) {
            case gl::Parameter::Type::integer: {
                int v = int(p.value);
                const float speed = float(std::max(1.0, (p.max - p.min) / 400.0));
                if (ImGui::DragInt(p.name.c_str(), &v, speed, int(p.min), int(p.max), "%d",
                                   ImGuiSliderFlags_AlwaysClamp)) {
                    text = fmt::format("{}", v);
                }
                break;
            }
            case gl::Parameter::Type::real: {
                double v = p.value;
                const bool logarithmic = p.min > 0.0 && p.max / p.min > 100.0;
                ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
                if (logarithmic)
                    flags |= ImGuiSliderFlags_Logarithmic;
                if (ImGui::SliderScalar(p.name.c_str(), ImGuiDataType_Double, &v, &p.min, &p.max,
                                        "%.4g", flags)) {
                    text = fmt::format("{}", v);
                }
                break;
            }
            case gl::Parameter::Type::choice: {
                if (ImGui::BeginCombo(p.name.c_str(), p.text().c_str())) {
                    for (const std::string& choice : p.choices) {
                        if (ImGui::Selectable(choice.c_str(), choice == p.text())) {
                            text = choice;
                            commit = true;
                        }
                    }
                    ImGui::EndCombo();
                }
                break;
            }
        }
        help_marker(p.description);
        commit |= ImGui::IsItemDeactivatedAfterEdit();
        if (text) {
            try {
                method_->set(p.name, *text);
            } catch (const Error& e) {
                status_ = e.what();
            }
        }
        if (commit) {
            prepare_method();  // parameters read in prepare() take effect
        }
    }
    if (!parameters.empty() && ImGui::Button("defaults")) {
        for (const gl::Parameter& p : parameters) {
            gl::Parameter d = p;
            d.value = p.default_value;
            method_->set(p.name, d.text());
        }
        prepare_method();
    }
}

void Viewer::ui_regions() {
    ImGui::Checkbox("volumes", &overlay_settings_.volumes);
    ImGui::SameLine();
    ImGui::Checkbox("outlines", &overlay_settings_.outlines);
    const char* names[3] = {"lit", "uncertain", "unlit"};
    for (int r = 0; r < 3; ++r) {
        const auto& c = kRegionColors[size_t(r)];
        ImGui::ColorButton(names[r], ImVec4(c[0], c[1], c[2], 1.0f), ImGuiColorEditFlags_NoTooltip,
                           ImVec2(12, 12));
        ImGui::SameLine();
        bool shown = overlay_settings_.regions[size_t(r)];
        if (ImGui::Checkbox(names[r], &shown))
            overlay_settings_.regions[size_t(r)] = shown;
        if (r < 2)
            ImGui::SameLine();
    }
    ImGui::SliderFloat("opacity", &overlay_settings_.opacity, 0.05f, 20.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("%zu beams; faces %zu / %zu / %zu", beams_, region_faces_[0], region_faces_[1],
                region_faces_[2]);
    if (influence_volume_ > 0.0) {
        ImGui::Text("volume: lit %.1f%%, uncertain %.1f%%, unlit %.1f%%",
                    100.0 * region_volume_[0] / influence_volume_,
                    100.0 * region_volume_[1] / influence_volume_,
                    100.0 * region_volume_[2] / influence_volume_);
    }
    ImGui::Text("beam tree %.2f ms, regions %.2f ms, prepare %.2f ms", tree_ms_, extract_ms_,
                prepare_ms_);
}

void Viewer::ui_view() {
    int mode = mode_ == CameraMode::orbit ? 0 : 1;
    ImGui::RadioButton("orbit", &mode, 0);
    ImGui::SameLine();
    ImGui::RadioButton("fly", &mode, 1);
    mode_ = mode == 0 ? CameraMode::orbit : CameraMode::fly;
    help_marker(
        "orbit: left drag turns about the target, right drag pans, wheel zooms.\n"
        "fly: drag looks, WASD/QE move (shift: faster), wheel sets the speed.\n"
        "ctrl + left/right drag moves the light's position/target.");
    ImGui::SliderFloat("fov", &scene_.camera.fov_y_degrees, 10.0f, 120.0f, "%.1f deg");
    ImGui::SliderFloat("exposure", &scene_.camera.exposure, 0.05f, 20.0f, "%.2f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Text("position %.2f %.2f %.2f", scene_.camera.position.x, scene_.camera.position.y,
                scene_.camera.position.z);
    ImGui::Text("target   %.2f %.2f %.2f", scene_.camera.target.x, scene_.camera.target.y,
                scene_.camera.target.z);
    if (mode_ == CameraMode::fly)
        ImGui::Text("fly speed %.2f m/s", fly_speed_);
    if (ImGui::Button("reset view")) {
        const Scene original = load_scene(options_.scene, SceneSearchPaths::defaults());
        scene_.camera = original.camera;
        controller_ = CameraController(scene_.camera);
    }
}

void Viewer::ui_light() {
    SpotLight& l = scene_.light;
    bool changed = false;
    changed |= ImGui::DragFloat3("position", &l.position.x, 0.02f);
    changed |= ImGui::DragFloat3("target", &l.target.x, 0.02f);
    changed |= ImGui::SliderFloat("cone", &l.cone_half_angle_degrees, 1.0f, 80.0f, "%.1f deg");
    changed |= ImGui::DragFloatRange2("range", &l.near, &l.far, 0.05f, 0.01f, 1000.0f);
    changed |= ImGui::DragFloat3("intensity", &l.intensity.x, 1.0f, 0.0f, 1e6f);
    changed |= ImGui::SliderFloat("falloff", &l.falloff_degrees, 0.0f, l.cone_half_angle_degrees,
                                  "%.1f deg");
    l.near = std::max(l.near, 1e-3f);
    l.far = std::max(l.far, l.near * 1.01f);
    l.falloff_degrees = std::min(l.falloff_degrees, l.cone_half_angle_degrees);
    if (changed && glm::length(l.target - l.position) > 1e-4f) {
        scene_changed();
    }
    ImGui::TextDisabled("ctrl + drag in the view moves it too");
}

void Viewer::ui_medium() {
    Medium& m = scene_.medium;
    bool changed = false;
    changed |= ImGui::DragFloat3("sigma_s", &m.sigma_s.x, 0.002f, 0.0f, 100.0f, "%.4f");
    changed |= ImGui::DragFloat3("sigma_a", &m.sigma_a.x, 0.002f, 0.0f, 100.0f, "%.4f");
    int phase = int(m.phase);
    if (ImGui::BeginCombo("phase", to_string(m.phase))) {
        for (int i = 0; i <= int(PhaseFunction::nishita_hazy); ++i) {
            if (ImGui::Selectable(to_string(PhaseFunction(i)), i == phase)) {
                m.phase = PhaseFunction(i);
                changed = true;
            }
        }
        ImGui::EndCombo();
    }
    changed |= ImGui::SliderFloat("g", &m.g, -0.99f, 0.99f);
    int model = int(m.model);
    if (ImGui::Combo("model", &model, "simplified\0physical\0")) {
        m.model = MediumModel(model);
        changed = true;
    }
    if (m.model == MediumModel::simplified) {
        changed |= ImGui::DragFloat("a0", &m.a0, 0.01f, 0.0f, 100.0f);
        changed |= ImGui::DragFloat("a1", &m.a1, 0.01f, 0.0f, 100.0f);
        if (m.a0 == 0.0f && m.a1 == 0.0f)
            m.a0 = 1e-3f;
    }
    if (changed) {
        scene_changed();
    }
}

void Viewer::ui_environment() {
    Environment& e = scene_.environment;
    static const std::vector<std::string> studio_lights = [] {
        std::vector<std::string> names;
        std::error_code ec;
        for (const auto& entry :
             std::filesystem::directory_iterator(SceneSearchPaths::defaults().environments, ec)) {
            if (entry.path().extension() == ".exr")
                names.push_back(entry.path().stem().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }();
    const std::string current = e.enabled() ? e.file.stem().string() : "none";
    if (ImGui::BeginCombo("environment", current.c_str())) {
        if (ImGui::Selectable("none", !e.enabled()))
            e.file.clear();
        for (const std::string& name : studio_lights) {
            if (ImGui::Selectable(name.c_str(), name == current))
                e.file = SceneSearchPaths::defaults().environments / (name + ".exr");
        }
        ImGui::EndCombo();
    }
    help_marker(
        "Blender's studio lights (Debian blender-data); a change bakes the chain again "
        "unless it is in the cache");
    if (!e.enabled())
        return;
    ImGui::SliderFloat("intensity", &e.intensity, 0.01f, 10.0f, "%.3f",
                       ImGuiSliderFlags_Logarithmic);
    ImGui::Checkbox("skybox", &e.skybox);
    int shading = e.shading == ibl::Shading::moschos ? 1 : 0;
    if (ImGui::Combo("shading", &shading, "split-sum\0moschos (alg. 7-8)\0"))
        e.shading = shading ? ibl::Shading::moschos : ibl::Shading::split_sum;
    // The rest is baked: edited on a copy, applied with the button.
    Environment& pending = environment_pending_;
    bool& editing = environment_editing_;
    if (!editing) {
        pending = e;
    }
    int method = pending.prefilter.method == ibl::PrefilterMethod::cone ? 1 : 0;
    editing |= ImGui::Combo("prefilter", &method, "importance\0cone (Moschos alg. 6)\0");
    pending.prefilter.method =
        method ? ibl::PrefilterMethod::cone : ibl::PrefilterMethod::importance;
    if (pending.prefilter.method == ibl::PrefilterMethod::importance) {
        int distribution = pending.prefilter.distribution == ibl::Distribution::beckmann ? 1 : 0;
        editing |= ImGui::Combo("distribution", &distribution, "ggx\0beckmann\0");
        pending.prefilter.distribution =
            distribution ? ibl::Distribution::beckmann : ibl::Distribution::ggx;
    }
    editing |= ImGui::SliderInt("samples", &pending.prefilter.samples, 1, 4096, "%d",
                                ImGuiSliderFlags_Logarithmic);
    int size_index = std::clamp(int(std::log2(float(pending.face_size))) - 5, 0, 5);
    editing |= ImGui::Combo("face size", &size_index,
                            "32\0"
                            "64\0"
                            "128\0"
                            "256\0"
                            "512\0"
                            "1024\0");
    pending.face_size = 32 << size_index;
    editing |=
        ImGui::SliderFloat("rotation", &pending.rotation_degrees, -180.0f, 180.0f, "%.0f deg");
    if (editing && ImGui::Button("bake")) {
        e.prefilter = pending.prefilter;
        e.face_size = pending.face_size;
        e.rotation_degrees = pending.rotation_degrees;
        editing = false;
    }
    if (renderer_ && renderer_->environment().loaded()) {
        const ibl::PrefilteredChain& chain = renderer_->environment().loaded()->chain;
        ImGui::Text("%zu levels of %d..%d texels, %s", chain.levels.size(),
                    chain.levels.front().size, chain.levels.back().size,
                    chain.seconds > 0 ? fmt::format("baked in {:.2f} s", chain.seconds).c_str()
                                      : "from the cache");
    }
}

void Viewer::ui_error() {
    bool on = layer("error");
    if (ImGui::Checkbox("show the error heat map", &on))
        layers_["error"] = on;
    ImGui::SliderFloat("full scale", &heat_scale_, 0.01f, 4.0f, "%.2f x RMS",
                       ImGuiSliderFlags_Logarithmic);
    help_marker("per-pixel |I_s - reference| relative to the reference's RMS pixel");
    if (!on)
        return;
    if (reference_) {
        ImGui::Text("rel_rmse %.4g, max_abs %.4g, psnr %.1f dB", error_.rel_rmse, error_.max_abs,
                    error_.psnr);
    } else if (job_) {
        ImGui::ProgressBar(float(job_->progress.load()), ImVec2(-1, 0), "computing reference");
    } else {
        ImGui::TextWrapped("No cached reference for this view and size.");
        if (ImGui::Button("compute it (CPU, in the background)")) {
            job_ = std::make_unique<ReferenceJob>();
            job_->thread = std::thread([job = job_.get(), scene = scene_, w = width_, h = height_,
                                        o = reference_options_] {
                try {
                    reference::cached_reference(scene, w, h, o,
                                                [job](double f) { job->progress = f; });
                } catch (const std::exception& e) {
                    job->error = e.what();
                }
                job->done = true;
            });
        }
    }
}

void Viewer::ui_save() {
    char buffer[512];
    std::snprintf(buffer, sizeof(buffer), "%s", save_path_.c_str());
    if (ImGui::InputText("file", buffer, sizeof(buffer)))
        save_path_ = buffer;
    if (ImGui::Button("save as experiment")) {
        try {
            const SavedView saved = save_view_as_experiment(
                save_path_, scene_, options_.scene, *method_, width_, height_, options_.shadow);
            saved_message_ = "saved " + saved.experiment.string();
        } catch (const Error& e) {
            status_ = e.what();
        }
    }
    ImGui::SameLine();
    if (ImGui::Button("screenshot"))
        take_screenshot_ = true;
    if (!saved_message_.empty())
        ImGui::TextWrapped("%s", saved_message_.c_str());
}

void Viewer::ui_timings() {
    ImGui::SetNextWindowPos(ImVec2(float(width_) - 368, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(360, 300), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("timings", &open);
    ImGui::Text("frame %.2f ms (%.1f fps), draw() %.2f ms CPU", frame_history_.latest(),
                1000.0 / std::max(frame_history_.latest(), 1e-3f), timings_.cpu_ms);
    ImGui::PlotLines("frame ms", frame_history_.values.data(), int(kHistory),
                     int(frame_history_.next), nullptr, 0.0f, frame_history_.max() * 1.1f,
                     ImVec2(0, 50));
    if (ImGui::BeginTable("passes", 2)) {
        auto row = [](const std::string& name, double ms) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%8.3f ms", ms);
        };
        row("GPU shadow map", timings_.gpu.shadow_ms);
        row("GPU surfaces", timings_.gpu.surface_ms);
        row("GPU volume", timings_.gpu.volume_ms);
        for (const auto& [name, ms] : timings_.gpu.volume_sections)
            row("    " + name, ms);
        row("GPU composite", timings_.gpu.composite_ms);
        row("CPU beam tree (viewer)", tree_ms_);
        row("CPU regions (viewer)", extract_ms_);
        row("CPU method prepare", prepare_ms_);
        for (const auto& [name, value] : statistics_) {
            if (name.starts_with("cpu_ms_"))
                row("CPU " + name.substr(7), value);
        }
        ImGui::EndTable();
    }
    for (auto [name, history] :
         {std::pair{"shadow", &shadow_history_}, std::pair{"surfaces", &surface_history_},
          std::pair{"volume", &volume_history_}, std::pair{"composite", &composite_history_}}) {
        ImGui::PlotLines(name, history->values.data(), int(kHistory), int(history->next),
                         fmt::format("{:.2f} ms", history->latest()).c_str(), 0.0f,
                         history->max() * 1.1f + 1e-3f, ImVec2(0, 32));
    }
    if (!statistics_.empty() && ImGui::TreeNode("method counters")) {
        for (const auto& [name, value] : statistics_) {
            ImGui::Text("%s = %.6g", name.c_str(), value);
        }
        ImGui::TreePop();
    }
    ImGui::End();
    if (!open)
        layers_["timings"] = false;
}

void Viewer::ui_previewer() {
    ImGui::SetNextWindowPos(ImVec2(float(width_) - 528, float(height_) - 400),
                            ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(520, 392), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("buffers", &open);
    const gl::TextureViews views = all_textures();
    const gl::TextureView* selected = nullptr;
    for (const gl::TextureView& view : views) {
        if (view.name == preview_name_)
            selected = &view;
    }
    if (!selected && !views.empty()) {
        selected = &views.front();
        preview_name_ = selected->name;
    }
    if (ImGui::BeginCombo("buffer", preview_name_.c_str())) {
        for (const gl::TextureView& view : views) {
            if (ImGui::Selectable(view.name.c_str(), view.name == preview_name_)) {
                preview_name_ = view.name;
                selected = &view;
            }
        }
        ImGui::EndCombo();
    }
    if (selected && selected->name != fitted_name_) {
        // A new buffer starts with its values' range.
        fitted_name_ = selected->name;
        std::tie(preview_settings_.lo, preview_settings_.hi) = value_range(
            selected->texture, preview_settings_.channel, preview_settings_.logarithmic);
    }
    if (selected) {
        const TextureInfo info = texture_info(selected->texture);
        ImGui::Text("%dx%d, format 0x%x%s", info.width, info.height, info.internal_format,
                    info.depth ? " (depth)" : "");
        ImGui::Combo("channel", &preview_settings_.channel, "rgb\0r\0g\0b\0a\0");
        ImGui::DragFloatRange2("range", &preview_settings_.lo, &preview_settings_.hi, 0.01f);
        ImGui::Checkbox("log10", &preview_settings_.logarithmic);
        ImGui::SameLine();
        if (ImGui::Button("fit range")) {
            const auto [lo, hi] = value_range(selected->texture, preview_settings_.channel,
                                              preview_settings_.logarithmic);
            preview_settings_.lo = lo;
            preview_settings_.hi = hi;
        }
        preview_.draw(selected->texture, preview_settings_, 480);
        GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
        const float width = std::min(ImGui::GetContentRegionAvail().x, float(preview_.width()));
        const float height = width * float(preview_.height()) / float(preview_.width());
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(preview_.preview())),
                     ImVec2(width, height), ImVec2(0, 1), ImVec2(1, 0));
    }
    ImGui::End();
    if (!open)
        layers_["previewer"] = false;
}

void Viewer::ui_light_view() {
    ImGui::SetNextWindowPos(ImVec2(356, float(height_) - 300), ImGuiCond_FirstUseEver);
    bool open = true;
    ImGui::Begin("light view of the leaves", &open, ImGuiWindowFlags_AlwaysAutoResize);
    ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(overlay_.light_view())),
                 ImVec2(kLightViewSize, kLightViewSize), ImVec2(0, 1), ImVec2(1, 0));
    ImGui::TextDisabled("leaves: open yellow, solid grey, blocker purple");
    ImGui::End();
    if (!open)
        layers_["light-view"] = false;
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace sl::viewer
