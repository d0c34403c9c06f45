#include "sampling/planes.h"

#include <array>
#include <chrono>
#include <cstddef>
#include <optional>

#include <glm/vec3.hpp>

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
#include "sampling/shaders/planes_interface.h"
#include "sampling/slices.h"

namespace sl::sampling {

namespace {

using frame::Parameter;
using gl::GL;

// The `partition` choices, in declaration order.
enum class Partition { gpu, cpu };

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

struct PlaneVertex {
    glm::vec3 position;
    float depth;
};

// Appends a convex polygon as a triangle fan.
void append_fan(const bt::Polygon& polygon, double depth, std::vector<PlaneVertex>& out) {
    for (size_t i = 1; i + 1 < polygon.size(); ++i) {
        for (size_t j : {size_t(0), i, i + 1}) {
            out.push_back({glm::vec3(polygon.vertices[j]), float(depth)});
        }
    }
}

const char* variant_name(PlanesVariant variant) {
    switch (variant) {
        case PlanesVariant::planes:
            return "planes";
        case PlanesVariant::hybrid1:
            return "hybrid1";
        case PlanesVariant::hybrid2:
            return "hybrid2";
    }
    return "?";
}

class PlanesMethod final : public frame::VolumeMethod {
public:
    explicit PlanesMethod(PlanesVariant variant)
        : VolumeMethod(variant_name(variant)), variant_(variant) {
        dz_ = declare_real("dz", 0.1, 1e-3, 100.0, "metres of eye depth between sampling planes");
        jitter_ = declare_flag("jitter", false,
                               "on: offset each pixel's sample within its slab (noise for bands)");
        declare_shadow_parameters();
        if (variant != PlanesVariant::planes) {
            partition_ = declare_choice(
                "partition", {"gpu", "cpu"}, Partition::gpu,
                "gpu: each plane sample classified by the beam tree on the GPU "
                "(beamtree/shaders/classify.glsl); cpu: every plane cut by the tree on the CPU "
                "each frame (Nilsson's method)");
            route_ = declare_choice("route", analytic::region_route_choices(),
                                    analytic::RegionRoute::automatic,
                                    analytic::region_route_description());
        }
    }

    std::string accepts() const override {
        return variant_ == PlanesVariant::hybrid2 ? analytic::AnalyticRegionPass::accepts()
                                                  : VolumeMethod::accepts();
    }

    void prepare_light(const Scene& scene) override {
        software_ = gl::current_renderer_is_software();  // for route = auto
        tree_.reset();
        update_light(scene, SceneChange::everything(scene));
        if (!program_) {
            program_ = gl::create_program({{GL_VERTEX_SHADER, "sampling/shaders/planes.vert"},
                                           {GL_FRAGMENT_SHADER, "sampling/shaders/planes.frag"}});
            vertex_buffer_ = gl::create_mutable_buffer();
            vertex_array_ = gl::create_vertex_array();
            const GLuint vao = vertex_array_.id();
            GL.VertexArrayVertexBuffer(vao, 0, vertex_buffer_.id(), 0, sizeof(PlaneVertex));
            GL.EnableVertexArrayAttrib(vao, SL_PLANES_POSITION_ATTRIBUTE);
            GL.VertexArrayAttribFormat(vao, SL_PLANES_POSITION_ATTRIBUTE, 3, GL_FLOAT, GL_FALSE, 0);
            GL.VertexArrayAttribBinding(vao, SL_PLANES_POSITION_ATTRIBUTE, 0);
            GL.EnableVertexArrayAttrib(vao, SL_PLANES_DEPTH_ATTRIBUTE);
            GL.VertexArrayAttribFormat(vao, SL_PLANES_DEPTH_ATTRIBUTE, 1, GL_FLOAT, GL_FALSE,
                                       offsetof(PlaneVertex, depth));
            GL.VertexArrayAttribBinding(vao, SL_PLANES_DEPTH_ATTRIBUTE, 0);
            vertex_array_.label("sampling planes");
            fragments_ = gl::create_query(GL_FRAGMENT_SHADER_INVOCATIONS);
        }
    }

    std::unique_ptr<frame::FrameWork> cpu_update_light(const Scene& scene,
                                                       const SceneChange& change) const override {
        if (variant_ == PlanesVariant::planes) {
            return nullptr;  // everything it draws is made from the frame's scene in render()
        }
        if (variant_ == PlanesVariant::hybrid2) {
            analytic::AnalyticRegionPass::require_closed_form(scene, name());
        }
        // The CPU partition cuts planes with the tree alone; the lists and the lit integral need
        // the meshes only on the mesh route.
        const bool walk = analytic::walks(*route_, scene, software_);
        return analytic::region_frame_work(
            scene, change,
            {.lit = !walk, .uncertain = !walk, .gpu_tree = true, .view_aspect = view_aspect()},
            tree_ != nullptr, walk);
    }
    void apply_update_light(const Scene& scene, const SceneChange&,
                            std::unique_ptr<frame::FrameWork> work) override {
        if (auto* regions = dynamic_cast<analytic::RegionFrameWork*>(work.get())) {
            const bt::FrameRegions& r = regions->regions;
            tree_ = r.tree;
            stages_ = r.ms;
            if (variant_ == PlanesVariant::hybrid2) {
                analytic_.upload_mesh(r.lit.positions, r.lit.triangles, scene.light,
                                      r.shared_sides);
            }
            lists_.upload(r.lit, r.uncertain);
            gpu_tree_.upload(r.gpu);
            walk_ = regions->walk;
        }
        if (variant_ == PlanesVariant::hybrid2) {
            analytic_.set_scene(scene);
        }
    }

    void render(const frame::VolumeInputs& inputs) override {
        const bool classify_on_gpu = tree_ && *partition_ == Partition::gpu;
        const PlaneDraws draws = upload_planes(inputs, classify_on_gpu);
        GLint target = 0;
        GL.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
        if (classify_on_gpu) {
            // The planes go to a target of their own with a stencil: the region lists mark the
            // pixels whose rays cross a region surface, and the planes are drawn only there.
            allocate(inputs.width, inputs.height);
            GL.BindFramebuffer(GL_FRAMEBUFFER, own_framebuffer_.id());
            const float zero[4] = {0, 0, 0, 0};
            GL.ClearNamedFramebufferfv(own_framebuffer_.id(), GL_COLOR, 0, zero);
            inputs.timeline.section("region lists");
            if (walk_) {
                lists_.walk(inputs, gpu_tree_, true, marked_bits());
            } else {
                lists_.build(inputs, true);
            }
        }
        if (variant_ == PlanesVariant::hybrid2) {
            GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
            draw_lit_integral(inputs, classify_on_gpu);
            if (classify_on_gpu) {
                GL.BindFramebuffer(GL_FRAMEBUFFER, own_framebuffer_.id());
            }
        }
        inputs.timeline.section("planes");
        draw_planes(inputs, draws, classify_on_gpu);
        if (classify_on_gpu) {
            GL.BindFramebuffer(GL_FRAMEBUFFER, GLuint(target));
            GL.UseProgram(copy_program_.id());
            GL.BindTextureUnit(0, own_target_.id());
            GL.BindVertexArray(empty_vertex_array_.id());
            GL.Enable(GL_BLEND);
            GL.BlendFunc(GL_ONE, GL_ONE);
            GL.DrawArrays(GL_TRIANGLES, 0, 3);  // added into the frame's I_s
            GL.Disable(GL_BLEND);
        }
    }

    // The pixels the region lists mark for the planes: hybrid1 draws its lit pieces too.
    GLuint marked_bits() const {
        return variant_ == PlanesVariant::hybrid1 ? analytic::RegionLists::kLitStencilBit |
                                                        analytic::RegionLists::kUncertainStencilBit
                                                  : analytic::RegionLists::kUncertainStencilBit;
    }

    // The vertex buffer's two ranges: pieces drawn with the shadow lookup, then (hybrid1) the
    // lit pieces drawn without it.
    struct PlaneDraws {
        GLsizei shadowed = 0, lit = 0;
    };

    // CPU: the planes clipped to the influence pyramid, then (hybrids) partitioned by the beam
    // tree (Nilsson appendix B `partition`, §5.2.1), uploaded as triangle fans.
    PlaneDraws upload_planes(const frame::VolumeInputs& inputs, bool classify_on_gpu) {
        auto start = std::chrono::steady_clock::now();
        const std::vector<Slice> slices =
            influence_slices(inputs.scene.camera, inputs.scene.light, *dz_);
        slicing_ms_ = ms_since(start);
        start = std::chrono::steady_clock::now();
        std::vector<PlaneVertex> vertices, lit;
        pieces_ = {};
        if (!tree_ || classify_on_gpu) {
            for (const Slice& slice : slices)
                append_fan(slice.polygon, slice.depth, vertices);
            pieces_[size_t(bt::Region::uncertain)] = slices.size();
        } else {
            const double tolerance = 1e-7 * double(inputs.scene.light.far);
            for (const Slice& slice : slices) {
                partition_slice(slice, tolerance, vertices, lit);
            }
        }
        const PlaneDraws draws{GLsizei(vertices.size()), GLsizei(lit.size())};
        vertices.insert(vertices.end(), lit.begin(), lit.end());
        partition_ms_ = tree_ && !classify_on_gpu ? ms_since(start) : 0.0;
        slice_count_ = slices.size();
        GL.NamedBufferData(vertex_buffer_.id(), GLsizeiptr(vertices.size() * sizeof(PlaneVertex)),
                           vertices.data(), GL_STREAM_DRAW);
        return draws;
    }

    void partition_slice(const Slice& slice, double tolerance, std::vector<PlaneVertex>& vertices,
                         std::vector<PlaneVertex>& lit) {
        bt::BeamTree::Partition parts = tree_->partition(slice.polygon);
        // Only pieces that are drawn can crack against each other.
        std::vector<bt::Polygon*> drawn;
        for (bt::Polygon& piece : parts.uncertain)
            drawn.push_back(&piece);
        if (variant_ == PlanesVariant::hybrid1) {
            for (bt::Polygon& piece : parts.lit)
                drawn.push_back(&piece);
        }
        remove_t_junctions(drawn, tolerance);
        for (const bt::Polygon& piece : parts.uncertain)
            append_fan(piece, slice.depth, vertices);
        if (variant_ == PlanesVariant::hybrid1) {
            for (const bt::Polygon& piece : parts.lit)
                append_fan(piece, slice.depth, lit);
        }
        pieces_[size_t(bt::Region::lit)] += parts.lit.size();
        pieces_[size_t(bt::Region::uncertain)] += parts.uncertain.size();
        pieces_[size_t(bt::Region::unlit)] += parts.unlit.size();
    }

    // hybrid2: the lit regions' closed form, into the frame's I_s.
    void draw_lit_integral(const frame::VolumeInputs& inputs, bool classify_on_gpu) {
        if (walk_ && !classify_on_gpu) {
            inputs.timeline.section("region lists");
            lists_.walk(inputs, gpu_tree_, false, 0);  // for the lit integral alone
        }
        inputs.timeline.section("analytic");
        if (walk_) {
            analytic_.draw_walk(inputs, gpu_tree_);
        } else {
            analytic_.draw(inputs);
        }
    }

    void draw_planes(const frame::VolumeInputs& inputs, PlaneDraws draws, bool classify_on_gpu) {
        std::optional<analytic::RegionLists::MarkedPixelsOnly> marked;
        if (classify_on_gpu) {
            marked.emplace(marked_bits());
        }
        GL.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS, fragments_.id());
        GL.UseProgram(program_.id());
        GL.ProgramUniform1f(program_.id(), SL_PLANES_DZ, float(*dz_));
        GL.ProgramUniform1i(program_.id(), SL_PLANES_JITTER, int(*jitter_));
        GL.ProgramUniform1i(program_.id(), SL_PLANES_CLASSIFY_MODE,
                            !classify_on_gpu                     ? 0
                            : variant_ == PlanesVariant::hybrid1 ? 1
                                                                 : 2);
        if (classify_on_gpu) {
            gpu_tree_.bind();
        }
        GL.BindTextureUnit(SL_PLANES_SURFACE_DEPTH_UNIT, inputs.surface_depth);
        GL.Enable(GL_BLEND);
        GL.BlendFunc(GL_ONE, GL_ONE);
        GL.Enable(GL_DEPTH_CLAMP);  // planes before the near plane still count
        GL.BindVertexArray(vertex_array_.id());
        GL.ProgramUniform1i(program_.id(), SL_PLANES_KNOWN_LIT, 0);
        GL.DrawArrays(GL_TRIANGLES, 0, draws.shadowed);
        if (draws.lit > 0) {
            GL.ProgramUniform1i(program_.id(), SL_PLANES_KNOWN_LIT, 1);
            GL.DrawArrays(GL_TRIANGLES, draws.shadowed, draws.lit);
        }
        GL.Disable(GL_DEPTH_CLAMP);
        GL.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS);
        GL.Disable(GL_BLEND);
    }

    void allocate(int width, int height) {
        if (width == own_width_ && height == own_height_) {
            return;
        }
        own_width_ = width;
        own_height_ = height;
        own_target_ = gl::create_texture_2d(GL_RGBA32F, width, height, GL_NEAREST);
        own_framebuffer_ = gl::create_framebuffer();
        GL.NamedFramebufferTexture(own_framebuffer_.id(), GL_COLOR_ATTACHMENT0, own_target_.id(),
                                   0);
        own_stencil_ = analytic::RegionLists::attach_marks(own_framebuffer_.id(), width, height);
        if (!copy_program_) {
            copy_program_ = gl::create_program({{GL_VERTEX_SHADER, "gl/shaders/fullscreen.vert"},
                                                {GL_FRAGMENT_SHADER, "gl/shaders/copy.frag"}});
            empty_vertex_array_ = gl::create_vertex_array();
        }
    }

    gl::TextureViews textures() const override { return analytic_.textures(name()); }

    frame::MethodStatistics statistics() const override {
        GLuint64 fragments = 0;
        GL.GetQueryObjectui64v(fragments_.id(), GL_QUERY_RESULT, &fragments);
        // cpu_ms_frame: the CPU work every frame (the volume cost's CPU part).
        frame::MethodStatistics stats = {{"cpu_ms_slicing", slicing_ms_},
                                         {"cpu_ms_frame", slicing_ms_ + partition_ms_},
                                         {"slices", double(slice_count_)},
                                         {"fragments", double(fragments)}};
        if (tree_) {
            const frame::MethodStatistics regions = analytic::region_statistics(stages_, walk_);
            stats.insert(stats.end(), regions.begin(), regions.end());
            stats.insert(stats.end(),
                         {{"cpu_ms_partition", partition_ms_},
                          {"pieces_lit", double(pieces_[size_t(bt::Region::lit)])},
                          {"pieces_uncertain", double(pieces_[size_t(bt::Region::uncertain)])},
                          {"pieces_unlit", double(pieces_[size_t(bt::Region::unlit)])}});
        }
        if (variant_ == PlanesVariant::hybrid2) {
            stats.emplace_back("region_faces", double(analytic_.triangle_count()));
            stats.emplace_back("fragments_analytic", analytic_.fragments());
            stats.emplace_back("fragments_rasterized", analytic_.rasterized());
        }
        return stats;
    }

private:
    PlanesVariant variant_;
    frame::Param<double> dz_;
    frame::Param<bool> jitter_;
    frame::Param<Partition> partition_;          // the hybrids'
    frame::Param<analytic::RegionRoute> route_;  // the hybrids'
    std::shared_ptr<const bt::BeamTree> tree_;
    bt::RegionStageTimes stages_;
    analytic::AnalyticRegionPass analytic_;
    gl::Program program_;
    gl::Buffer vertex_buffer_;
    analytic::GpuTreeBuffers gpu_tree_;  // the tree for the GPU's classify (and walk)
    bool walk_ = false;      // the last build was for the walk route (never for `planes`: no build)
    bool software_ = false;  // the GL is a software rasterizer (prepare())
    analytic::RegionLists lists_;
    // partition = gpu: the planes' own target and stencil, added into the frame's I_s.
    gl::Texture own_target_, own_stencil_;
    gl::Framebuffer own_framebuffer_;
    gl::Program copy_program_;
    gl::VertexArray empty_vertex_array_;
    int own_width_ = 0, own_height_ = 0;
    gl::VertexArray vertex_array_;
    gl::Query fragments_;
    size_t slice_count_ = 0;
    std::array<size_t, 3> pieces_{};
    double slicing_ms_ = 0.0, partition_ms_ = 0.0;
};

}  // namespace

void register_planes_methods(frame::MethodRegistry& registry) {
    int order = 20;
    for (const PlanesVariant variant :
         {PlanesVariant::planes, PlanesVariant::hybrid1, PlanesVariant::hybrid2}) {
        registry.add(variant_name(variant), order++,
                     [variant] { return std::make_unique<PlanesMethod>(variant); });
    }
}

}  // namespace sl::sampling
