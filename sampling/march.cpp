#include "sampling/march.h"

#include <chrono>
#include <cmath>
#include <optional>

#include "analytic/region_lists.h"
#include "analytic/region_pass.h"
#include "beamtree/beam_tree.h"
#include "beamtree/boundary.h"
#include "beamtree/regions.h"
#include "core/error.h"
#include "frame/method_registry.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/platform.h"
#include "gl/shaders.h"
#include "sampling/shaders/march_interface.h"

namespace sl::sampling {

namespace {

using gl::GL;

// The choices, in the order they are declared and numbered in the shaders (march.frag's
// clip_mode and attenuation, march_resolve.frag's blur).
enum class Blur { none, gauss5, depth_aware };
enum class ResolutionScale { full, half, quarter };
enum class Clip { off, pyramid, cone };
enum class Attenuation { model, moschos };

class MarchMethod final : public frame::VolumeMethod {
public:
    explicit MarchMethod(MarchVariant variant)
        : VolumeMethod(variant == MarchVariant::march ? "march" : "hybrid3"), variant_(variant) {
        samples_ = declare_integer("samples", 64, 1, 4096,
                                   variant == MarchVariant::march
                                       ? "samples per eye ray over its clipped trace"
                                       : "the most samples an eye ray spends on its uncertain "
                                         "intervals");
        if (variant == MarchVariant::hybrid3) {
            density_ = declare_real("density", 256.0, 1e-3, 1e7,
                                    "samples per metre of uncertain interval: N = clamp(ceil("
                                    "density x length), min_samples, samples)");
            route_ = declare_choice("route", analytic::region_route_choices(),
                                    analytic::RegionRoute::automatic,
                                    analytic::region_route_description());
            min_samples_ = declare_integer("min_samples", 2, 1, 4096,
                                           "the fewest samples a ray with any uncertain length "
                                           "gets");
        }
        resolution_scale_ =
            declare_choice("resolution_scale", {"1", "0.5", "0.25"}, ResolutionScale::full,
                           "size of the marching buffer relative to the frame");
        blur_ = declare_choice("blur", {"none", "gauss5", "depth_aware"}, Blur::none,
                               "none; gauss5 (Moschos alg. 3); depth_aware (no bleeding)");
        jitter_ = declare_flag("jitter", false,
                               "on: per-pixel offset of the samples (interleaved gradient noise)");
        declare_shadow_parameters();
        if (variant == MarchVariant::march) {
            clip_ = declare_choice("clip", {"off", "pyramid", "cone"}, Clip::cone,
                                   "off; pyramid (Moschos alg. 4); cone (exact cone and range)");
            attenuation_ = declare_choice(
                "attenuation", {"model", "moschos"}, Attenuation::model,
                "model (the reference's); moschos (eq. 3.1, does NOT match the reference)");
            optical_thickness_ = declare_real("optical_thickness", 15.0, 1e-3, 1e6,
                                              "metres: l of Moschos eq. 3.1 (attenuation=moschos)");
            animate_phase_ = declare_flag("animate_phase", false,
                                          "on: the phase function's g drifts with time and place");
        }
    }

    std::string accepts() const override {
        return variant_ == MarchVariant::hybrid3 ? analytic::AnalyticRegionPass::accepts()
                                                 : VolumeMethod::accepts();
    }

    void prepare_light(const Scene& scene) override {
        software_ = gl::current_renderer_is_software();  // for route = auto
        built_ = false;
        update_light(scene, SceneChange::everything(scene));
        if (!march_program_) {
            march_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "sampling/shaders/march.frag"}});
            resolve_program_ =
                gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                    {GL_FRAGMENT_SHADER, "sampling/shaders/march_resolve.frag"}});
            empty_vertex_array_ = gl::create_vertex_array();
        }
        frame_index_ = 0;
    }

    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene& scene,
                                                       const SceneChange& change) const override {
        if (variant_ != MarchVariant::hybrid3) {
            return nullptr;
        }
        analytic::AnalyticRegionPass::require_closed_form(scene, name());
        const bool walk = analytic::walks(*route_, scene, software_);
        return analytic::region_frame_work(
            scene, change,
            {.lit = !walk, .uncertain = !walk, .gpu_tree = true, .view_aspect = view_aspect()},
            built_, walk);
    }
    void apply_update_light(const Scene& scene, const SceneChange&,
                            std::unique_ptr<frame::FrameWork> work) override {
        if (auto* regions = dynamic_cast<analytic::RegionFrameWork*>(work.get())) {
            const bt::FrameRegions& r = regions->regions;
            stages_ = r.ms;
            analytic_.upload_mesh(r.lit.positions, r.lit.triangles, scene.light, r.shared_sides);
            lists_.upload(bt::RegionMesh{}, r.uncertain);
            tree_.upload(r.gpu);
            walk_ = regions->walk;
            built_ = true;
        }
        if (variant_ == MarchVariant::hybrid3) {
            analytic_.set_scene(scene);
        }
        // The march clips each ray to the influence pyramid of the frame's light.
        clip_planes_.clear();
        for (const bt::Plane& plane : bt::influence_planes(scene.light)) {
            clip_planes_.insert(clip_planes_.end(), {float(plane.normal.x), float(plane.normal.y),
                                                     float(plane.normal.z), float(plane.offset)});
        }
    }

    void render(const frame::VolumeInputs& inputs) override {
        GLint target = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        const double scale = *resolution_scale_ == ResolutionScale::full   ? 1.0
                             : *resolution_scale_ == ResolutionScale::half ? 0.5
                                                                           : 0.25;
        allocate(inputs.width, inputs.height, scale);
        const bool hybrid = variant_ == MarchVariant::hybrid3;
        // hybrid3 with a marching buffer of the frame's size: the region lists mark the pixels
        // whose rays cross the uncertain surface in the buffer's stencil, and the march shades
        // only those (a ray that crosses none has no uncertain interval: it adds nothing). The
        // rest of the buffer keeps its clear, so the image is the same.
        const bool skip_certain = hybrid && march_stencil_;
        if (hybrid) {
            draw_regions(inputs, GLuint(target), skip_certain);
        }
        // A marching buffer of the frame's size without blur needs no resolve (it would copy):
        // the march adds its I_s straight into the frame's target, attached beside the buffer.
        const GLuint direct_target =
            scale == 1.0 && *blur_ == Blur::none ? frame_texture(GLuint(target)) : 0;
        if (direct_target) {
            attach_frame_target(direct_target);
        }
        inputs.timeline.section("march");
        march(inputs, scale, direct_target != 0, skip_certain);
        GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
        GL.Viewport(0, 0, inputs.width, inputs.height);
        if (direct_target) {
            GL.Disablei(GL_BLEND, 1);
            attach_frame_target(0);
            return;
        }
        inputs.timeline.section("resolve");
        resolve(inputs, scale);
    }

    // hybrid3: the region lists (marking the uncertain pixels when `skip_certain`) and the lit
    // regions' closed form, into the frame's target.
    void draw_regions(const frame::VolumeInputs& inputs, GLuint target, bool skip_certain) {
        inputs.timeline.section("region lists");
        if (skip_certain) {
            GL.BindFramebuffer(GL_FRAMEBUFFER, march_framebuffer_.id());
        }
        if (walk_) {
            lists_.walk(inputs, tree_, skip_certain, analytic::RegionLists::kUncertainStencilBit);
        } else {
            lists_.build(inputs, skip_certain);
        }
        GL.BindFramebuffer(GL_FRAMEBUFFER, target);
        inputs.timeline.section("analytic");
        if (walk_) {
            analytic_.draw_walk(inputs, tree_);
        } else {
            analytic_.draw(inputs);
        }
        tree_.bind();
    }

    // The march into the marching buffer (and, when `direct`, added into the frame's I_s
    // attached beside it).
    void march(const frame::VolumeInputs& inputs, double scale, bool direct, bool skip_certain) {
        const bool hybrid = variant_ == MarchVariant::hybrid3;
        GL.BindFramebuffer(GL_FRAMEBUFFER, march_framebuffer_.id());
        GL.Viewport(0, 0, buffer_width_, buffer_height_);
        const float zero[4] = {0, 0, 0, 0};
        GL.ClearNamedFramebufferfv(march_framebuffer_.id(), GL_COLOR, 0, zero);
        GL.Disable(GL_BLEND);
        if (direct) {
            GL.Enablei(GL_BLEND, 1);  // added into the frame's I_s
            GL.BlendFunci(1, GL_ONE, GL_ONE);
        }
        std::optional<analytic::RegionLists::MarkedPixelsOnly> marked;
        if (skip_certain) {
            marked.emplace(analytic::RegionLists::kUncertainStencilBit);
        }
        const GLuint program = march_program_.id();
        GL.UseProgram(program);
        GL.ProgramUniform1i(program, SL_MARCH_SAMPLES, *samples_);
        GL.ProgramUniform1i(program, SL_MARCH_JITTER, int(*jitter_));
        GL.ProgramUniform1i(program, SL_MARCH_CLIP_MODE, hybrid ? int(Clip::cone) : int(*clip_));
        GL.ProgramUniform1f(program, SL_MARCH_BUFFER_SCALE, float(scale));
        GL.ProgramUniform1i(program, SL_MARCH_ATTENUATION,
                            hybrid ? int(Attenuation::model) : int(*attenuation_));
        GL.ProgramUniform1f(program, SL_MARCH_OPTICAL_THICKNESS,
                            hybrid ? 1.0f : float(*optical_thickness_));
        GL.ProgramUniform1i(program, SL_MARCH_ANIMATE_PHASE, hybrid ? 0 : int(*animate_phase_));
        GL.ProgramUniform1f(program, SL_MARCH_TIME, float(frame_index_++) / 60.0f);
        GL.ProgramUniform1i(program, SL_MARCH_INTERVAL_MODE, hybrid ? 1 : 0);
        if (hybrid) {
            GL.ProgramUniform2f(program, SL_MARCH_ADAPTIVE, float(*density_), float(*min_samples_));
        }
        GL.ProgramUniform4fv(program, SL_MARCH_CLIP_PLANES, 6, clip_planes_.data());
        GL.BindTextureUnit(SL_MARCH_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        GL.BindVertexArray(empty_vertex_array_.id());
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
    }

    // The marching buffer upsampled (and blurred) into the frame's target, added.
    void resolve(const frame::VolumeInputs& inputs, double scale) {
        GL.UseProgram(resolve_program_.id());
        GL.ProgramUniform1f(resolve_program_.id(), SL_RESOLVE_BUFFER_SCALE, float(scale));
        GL.ProgramUniform1i(resolve_program_.id(), SL_RESOLVE_BLUR, int(*blur_));
        GL.BindTextureUnit(SL_RESOLVE_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        GL.BindTextureUnit(SL_RESOLVE_MARCHED_UNIT, march_target_.id());
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.DrawArrays(GL_TRIANGLES, 0, 3);
        GL.Disable(GL_BLEND);
    }

    frame::MethodStatistics statistics() const override {
        // Samples evaluated: the marching buffer's alpha, summed (read back here, not timed).
        std::vector<float> rgba(size_t(buffer_width_) * buffer_height_ * 4);
        GL.GetTextureImage(march_target_.id(), 0, GL_RGBA, GL_FLOAT,
                           GLsizei(rgba.size() * sizeof(float)), rgba.data());
        double samples = 0.0;
        for (size_t i = 3; i < rgba.size(); i += 4)
            samples += rgba[i];
        frame::MethodStatistics stats = {{"samples_evaluated", samples},
                                         {"buffer_width", double(buffer_width_)},
                                         {"buffer_height", double(buffer_height_)}};
        if (variant_ == MarchVariant::hybrid3) {
            const frame::MethodStatistics regions = analytic::region_statistics(stages_, walk_);
            stats.insert(stats.end(), regions.begin(), regions.end());
            stats.insert(stats.end(), {{"region_faces", double(analytic_.triangle_count())},
                                       {"uncertain_faces", double(lists_.triangle_count(1))},
                                       {"fragments_analytic", analytic_.fragments()},
                                       {"fragments_rasterized", analytic_.rasterized()},
                                       {"list_overflows", double(lists_.overflows())}});
        }
        return stats;
    }

    gl::TextureViews textures() const override {
        if (!march_target_) {
            return {};
        }
        gl::TextureViews views = {
            {name() + "/marching buffer (rgb I_s, a samples)", march_target_.id()}};
        if (variant_ == MarchVariant::hybrid3) {
            for (gl::TextureView& view : analytic_.textures(name())) {
                views.push_back(std::move(view));
            }
        }
        return views;
    }

private:
    frame::Param<int> samples_;
    frame::Param<double> density_;               // hybrid3
    frame::Param<analytic::RegionRoute> route_;  // hybrid3
    frame::Param<int> min_samples_;              // hybrid3
    frame::Param<ResolutionScale> resolution_scale_;
    frame::Param<Blur> blur_;
    frame::Param<bool> jitter_;
    frame::Param<Clip> clip_;                 // march
    frame::Param<Attenuation> attenuation_;   // march
    frame::Param<double> optical_thickness_;  // march
    frame::Param<bool> animate_phase_;        // march
    // The texture behind the frame target's first colour attachment, or 0 (the default
    // framebuffer, a renderbuffer): the march then resolves into the target instead.
    static GLuint frame_texture(GLuint framebuffer) {
        if (framebuffer == 0) {
            return 0;
        }
        GLint type = GL_NONE, name = 0;
        GL.GetNamedFramebufferAttachmentParameteriv(framebuffer, GL_COLOR_ATTACHMENT0,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE, &type);
        if (type != GL_TEXTURE) {
            return 0;
        }
        GL.GetNamedFramebufferAttachmentParameteriv(framebuffer, GL_COLOR_ATTACHMENT0,
                                                    GL_FRAMEBUFFER_ATTACHMENT_OBJECT_NAME, &name);
        return GLuint(name);
    }

    // The marching buffer draws to attachment 0 and, with a frame texture, to it at attachment 1
    // (march.frag's `added`); with 0, to attachment 0 alone. The frame's texture is attached for
    // the march pass only, so the buffer never holds one the renderer has since replaced.
    void attach_frame_target(GLuint texture) {
        GL.NamedFramebufferTexture(march_framebuffer_.id(), GL_COLOR_ATTACHMENT1, texture, 0);
        const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0,
                                   texture ? GLenum(GL_COLOR_ATTACHMENT1) : GLenum(GL_NONE)};
        GL.NamedFramebufferDrawBuffers(march_framebuffer_.id(), 2, buffers);
    }

    void allocate(int width, int height, double scale) {
        const int w = std::max(1, int(std::ceil(width * scale)));
        const int h = std::max(1, int(std::ceil(height * scale)));
        if (w == buffer_width_ && h == buffer_height_ && frame_width_ == width &&
            frame_height_ == height)
            return;
        buffer_width_ = w;
        buffer_height_ = h;
        frame_width_ = width;
        frame_height_ = height;
        march_target_ = gl::create_texture_2d(GL_RGBA32F, w, h, GL_NEAREST);
        march_target_.label("marching buffer");
        march_framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(march_framebuffer_.id(), GL_COLOR_ATTACHMENT0,
                                   march_target_.id(), 0);
        march_stencil_ = {};
        if (variant_ == MarchVariant::hybrid3 && w == width && h == height) {
            march_stencil_ = analytic::RegionLists::attach_marks(march_framebuffer_.id(), w, h);
        }
    }

    MarchVariant variant_;
    analytic::AnalyticRegionPass analytic_;
    gl::Program march_program_, resolve_program_;
    gl::VertexArray empty_vertex_array_;
    gl::Texture march_target_;
    gl::Texture march_stencil_;  // hybrid3 at the frame's size: the pixels it marches
    gl::Framebuffer march_framebuffer_;
    analytic::RegionLists lists_;    // hybrid3: where each ray is uncertain
    analytic::GpuTreeBuffers tree_;  // and the tree, where a list overflows (or to walk)
    bool walk_ = false;              // the last build was for the walk route
    bool software_ = false;          // the GL is a software rasterizer (prepare())
    std::vector<float> clip_planes_;
    int buffer_width_ = 0, buffer_height_ = 0, frame_width_ = 0, frame_height_ = 0;
    int frame_index_ = 0;
    bt::RegionStageTimes stages_;
    bool built_ = false;
};

}  // namespace

void register_march_methods(frame::MethodRegistry& registry) {
    registry.add("march", 30, [] { return std::make_unique<MarchMethod>(MarchVariant::march); });
    registry.add("hybrid3", 31,
                 [] { return std::make_unique<MarchMethod>(MarchVariant::hybrid3); });
}

}  // namespace sl::sampling
