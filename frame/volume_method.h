#pragma once
// The interface every volumetric method implements (docs/design.md §3): given the scene and the
// frame's buffers, add the in-scattered radiance I_s of Nilsson eq. 2.7 into the bound target.
// The renderer, the harness and the viewer talk to methods only through this interface; methods
// live in their family's folders and are created by name from the registry (methods/registry.h).

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "frame/parameters.h"
#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders/frame_uniforms.h"
#include "gl/texture_view.h"
#include "scenes/animation.h"
#include "scenes/scene.h"

namespace sl::frame {

// How the frame's shadow map is made and filtered (surfaces and mid-air lookups alike):
//   hard  one depth comparison per lookup;
//   pcf   (2r+1)² bilinear depth comparisons (Reeves et al. 1987);
//   vsm   variance shadow map (Donnelly & Lauritzen 2006, Nilsson's choice): the first two moments
//         of the light's linear depth, blurred (2r+1)² and bounded by Chebyshev's inequality.
enum class ShadowFilter { hard, pcf, vsm };
const char* to_string(ShadowFilter filter);
ShadowFilter parse_shadow_filter(const std::string& text);  // throws sl::Error naming the choices

struct ShadowSettings {
    ShadowFilter filter = ShadowFilter::pcf;
    int map_size = 2048;
    int radius = 1;  // PCF taps or VSM blur: (2r+1)²
    bool operator==(const ShadowSettings&) const = default;
};

// The volume pass's GPU time split into named sections (GL_TIME_ELAPSED queries may not nest):
// starting a section ends the previous one. Time before the first section is the method's
// "setup"; the renderer sums the sections into the volume pass.
class PassTimeline {
public:
    virtual ~PassTimeline() = default;
    virtual void section(const char* name) = 0;
};

struct VolumeInputs {
    const Scene& scene;
    const gl::shared::FrameUniforms& uniforms;  // also bound as the uniform block at its binding
    GLuint surface_depth;                       // camera depth buffer (depth texture)
    GLuint shadow_map;  // light depth buffer (depth texture, compare mode), also bound at
                        // SL_SHADOW_MAP_UNIT with the VSM moments at SL_SHADOW_MOMENTS_UNIT
    int width;
    int height;
    PassTimeline& timeline;
};

// A named per-frame counter a method reports (slices, pieces, fragments, CPU time of a stage).
using MethodStatistics = std::vector<std::pair<std::string, double>>;

// What a method's per-frame update computed on the CPU (a beam tree and its meshes), handed from
// cpu_update() to apply_update(); methods define their own.
struct FrameWork {
    virtual ~FrameWork() = default;
};

class VolumeMethod {
public:
    virtual ~VolumeMethod() = default;
    VolumeMethod(const VolumeMethod&) = delete;
    VolumeMethod& operator=(const VolumeMethod&) = delete;

    // The name it is registered, configured and reported under.
    const std::string& name() const { return name_; }

    // Its parameters by name, as configs, the command line and the viewer set them
    // (frame/parameters.h); the method itself reads them through the typed handles it declared.
    const std::vector<Parameter>& parameters() const { return parameters_.all(); }
    bool has_parameter(const std::string& name) const { return parameters_.has(name); }
    // The parameter as declared, with its current value; throws sl::Error naming the known ones.
    const Parameter& find(const std::string& name) const { return parameters_.find(name); }
    // Parses and sets one parameter (in every light's copy too); throws sl::Error naming the
    // method and the parameter when the name is unknown, the text is not a value of its type, or
    // it is out of range.
    void set(const std::string& name, const std::string& text);
    // Checks what one parameter's range cannot say (a combination of parameters); throws
    // sl::Error naming the parameters. Called once a method is configured
    // (methods/configured_method.h) and whenever the viewer changes a value, so that bad input
    // fails before a frame is drawn.
    virtual void validate() const {}

    // The media and lights the method integrates (`shaftlab methods`, docs/methods.md): every one
    // the scene format allows unless it says otherwise; prepare() refuses the others by name.
    virtual std::string accepts() const {
        return "every medium and light: spot lights (cone or pyramid), point lights and "
               "directional lights, any number (it samples e(z) itself)";
    }
    // Several lights (docs/design.md §17): I_s sums over the scene's spot lights
    // (Scene::spot_lights, a point light counting as its six faces), each with its own instance
    // of the method: this one for the first, and for each further light a copy of it (the same
    // method with the same parameter values), each prepared and updated with the scene as its
    // light alone sees it (Scene::for_light). The methods implement the per-light hooks below;
    // the renderer draws each light's shadow map and calls for_light(i).render() for it.
    size_t light_count() const { return 1 + copies_.size(); }
    // True for a method that sums over the lights itself (the reference, `none`): one instance,
    // prepared with the whole scene, whose render() the renderer calls once, with the whole scene,
    // after every light's shadow map and surfaces.
    virtual bool takes_every_light() const { return false; }
    VolumeMethod& for_light(size_t index);
    const VolumeMethod& for_light(size_t index) const;

    // The frames' width / height, where the caller knows it before prepare(): a method may fit
    // what it builds on the CPU to what the camera sees at it (a sun's beam tree:
    // beamtree/frame_regions.h), and update it when the camera moves. 0, the default: nothing is
    // fitted to a view. Set in every light's copy too; takes effect at the next prepare().
    void set_view_aspect(float aspect);
    float view_aspect() const { return view_aspect_; }

    // Called once per scene before the first frame: programs, buffers, and the scene's state as
    // update(scene, SceneChange::everything(scene)) would make it, for every light.
    void prepare(const Scene& scene);

    // The per-frame update (docs/design.md §10): `scene` is the frame's scene, `change` what
    // differs from the scene of the last prepare() or update(). In two halves, so that the
    // pipelined frame loop (frame/frame_loop.h) can run the CPU half on a worker thread while the
    // GPU draws the previous frame with this method:
    //   cpu_update    no GL and no state that render() reads (it may run during render());
    //                 returns what apply_update() installs, or null when nothing is needed;
    //   apply_update  on the GL thread between frames: uploads, tables, programs.
    // Both throw sl::Error as prepare() would. A change in the number of lights prepares again.
    std::unique_ptr<FrameWork> cpu_update(const Scene& scene, const SceneChange& change) const;
    void apply_update(const Scene& scene, const SceneChange& change,
                      std::unique_ptr<FrameWork> work);
    // Both halves in turn (the serial mode).
    void update(const Scene& scene, const SceneChange& change) {
        apply_update(scene, change, cpu_update(scene, change));
    }
    // Adds I_s (linear RGB, alpha ignored) into the bound framebuffer, blending ONE, ONE; it
    // neither reads that target nor writes it otherwise. The target holds the I_s of the lights
    // drawn before this one (zero for the first: several lights sum there, docs/design.md §17)
    // and has no depth attachment; the viewport covers it.
    virtual void render(const VolumeInputs& inputs) = 0;
    // Counters of the last frame rendered (empty by default); may wait for the GPU. Of this
    // light's instance alone; frame_statistics() sums each over the lights (sizes too, such as a
    // grid's: with several lights it adds `lights`, their number, to divide those by).
    virtual MethodStatistics statistics() const { return {}; }
    MethodStatistics frame_statistics() const;
    // The method's own textures of the last frame (render targets, lookup tables).
    virtual gl::TextureViews textures() const { return {}; }
    // The shadow map the method asks for: `frame` with the filter and the size replaced by the
    // method's `shadow` and `shadow_size` parameters, where it declared them.
    ShadowSettings shadow_settings(ShadowSettings frame) const;

protected:
    explicit VolumeMethod(std::string name) : name_(name), parameters_(std::move(name)) {}

    // The per-light hooks: prepare(), cpu_update() and apply_update() above for a scene of one
    // light (Scene::lights empty), called once per light. cpu_update() runs the lights'
    // cpu_update_light() on parallel tasks, each on its own light's instance: it reads only that
    // instance and locks whatever it shares with the others.
    virtual void prepare_light(const Scene& scene) = 0;
    virtual std::unique_ptr<FrameWork> cpu_update_light(const Scene& scene,
                                                        const SceneChange& change) const = 0;
    virtual void apply_update_light(const Scene& scene, const SceneChange& change,
                                    std::unique_ptr<FrameWork> work) = 0;
    // Both per-light halves in turn: what a method's prepare_light() calls to bring itself to its
    // scene (update() would treat that scene, of one light, as all of them).
    void update_light(const Scene& scene, const SceneChange& change) {
        apply_update_light(scene, change, cpu_update_light(scene, change));
    }
    // A new, unprepared instance of this method with its default parameters: the factory the
    // registry made it with (frame/method_registry.h); a method made otherwise overrides this to
    // take several lights.
    virtual std::unique_ptr<VolumeMethod> make_instance() const;

    // Declarations, in the constructor: each returns the handle the method reads the value with.
    Param<int> declare_integer(std::string name, int default_value, int min, int max,
                               std::string description) {
        return parameters_.integer(std::move(name), default_value, min, max,
                                   std::move(description));
    }
    Param<double> declare_real(std::string name, double default_value, double min, double max,
                               std::string description) {
        return parameters_.real(std::move(name), default_value, min, max, std::move(description));
    }
    Param<bool> declare_flag(std::string name, bool default_value, std::string description) {
        return parameters_.flag(std::move(name), default_value, std::move(description));
    }
    template <class Enum>
    Param<Enum> declare_choice(std::string name, std::vector<std::string> choices,
                               Enum default_value, std::string description) {
        return parameters_.choice(std::move(name), std::move(choices), default_value,
                                  std::move(description));
    }
    // Declares `shadow` (hard, pcf, vsm; `filter` by default) and `shadow_size`, which
    // shadow_settings() reads.
    void declare_shadow_parameters(ShadowFilter filter = ShadowFilter::pcf);
    // Declares `shadow_size` alone (a method that takes the frame's filter as it is).
    void declare_shadow_size(std::string description);

private:
    friend class MethodRegistry;  // sets factory_
    std::string name_;
    ParameterSet parameters_;
    std::function<std::unique_ptr<VolumeMethod>()> factory_;
    std::vector<std::unique_ptr<VolumeMethod>> copies_;  // lights 1, 2, ...: see light_count()
    Param<ShadowFilter> shadow_filter_;
    Param<int> shadow_size_;
    float view_aspect_ = 0.0f;
};

// `none`: no participating medium is rendered, I_s = 0; the frame is the surfaces alone
// (I_obj·T(Z)). The baseline every method's cost is measured against.
std::unique_ptr<VolumeMethod> create_no_volume();

}  // namespace sl::frame
