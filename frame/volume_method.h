#pragma once
// The interface every volumetric method implements (docs/design.md §3): given the scene and the
// frame's buffers, add the in-scattered radiance I_s of Nilsson eq. 2.7 into the bound target.
// The renderer, the harness and the viewer talk to methods only through this interface; methods
// live in their family's folders and are created by name from the registry (methods/registry.h).

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

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

// A parameter a method declares (Mitsuba style: documented where it is read), settable from the
// command line (`--set name=value`), configs and the viewer, and written back by name:
//   integer, real  a number in [min, max];
//   boolean        true or false (also written on and off, or the old spellings 1 and 0);
//   choice         an enumeration: the index of one of `choices`, set and written by its name.
// Methods read them typed: number(), flag(), choice<Enum>() (the enum's values in the order of
// `choices`) or choice_name().
struct Parameter {
    enum class Type { integer, real, boolean, choice };
    std::string name;
    Type type = Type::real;
    double value = 0.0;
    double default_value = 0.0;
    double min = 0.0;
    double max = 0.0;
    std::string description{};
    std::vector<std::string> choices{};

    // The value as text: a number, true or false, or the chosen name.
    std::string text() const;
    // The type's name as `shaftlab methods` prints it: integer, real, bool or enum.
    const char* type_name() const;
};

// What a method's per-frame update computed on the CPU (a beam tree and its meshes), handed from
// cpu_update() to apply_update(); methods define their own.
struct FrameWork {
    virtual ~FrameWork() = default;
};

class VolumeMethod {
public:
    virtual ~VolumeMethod() = default;
    const std::vector<Parameter>& parameters() const { return parameters_; }
    // The value of a number parameter (integer or real); throws sl::Error for a flag or a choice,
    // which are read with flag() and choice().
    double number(const std::string& name) const;
    bool flag(const std::string& name) const;
    // The chosen name, or the choice as the enum whose values follow `choices`.
    const std::string& choice_name(const std::string& name) const;
    template <class Enum>
    Enum choice(const std::string& name) const {
        return Enum(choice_index(name));
    }
    // The parameter as declared, with its current value; throws sl::Error naming the known ones.
    const Parameter& find(const std::string& name) const;
    // Parses and sets one parameter; throws sl::Error naming the method and the parameter when
    // the name is unknown, the text is not a number of its type, or it is out of range.
    void set(const std::string& name, const std::string& text);
    virtual std::string name() const = 0;
    // The media and lights the method integrates (`shaftlab methods`, docs/methods.md): every one
    // the scene format allows unless it says otherwise; prepare() refuses the others by name.
    virtual std::string accepts() const {
        return "every medium and light (it samples e(z) itself)";
    }
    // Called once per scene before the first frame: programs, buffers, and the scene's state as
    // update(scene, SceneChange::everything(scene)) would make it.
    virtual void prepare(const Scene& scene) = 0;

    // The per-frame update (docs/design.md §10): `scene` is the frame's scene, `change` what
    // differs from the scene of the last prepare() or update(). In two halves, so that the
    // pipelined frame loop (gl/frame_loop.h) can run the CPU half on a worker thread while the GPU
    // draws the previous frame with this method:
    //   cpu_update    no GL and no state that render() reads (it may run during render());
    //                 returns what apply_update() installs, or null when nothing is needed;
    //   apply_update  on the GL thread between frames: uploads, tables, programs.
    // Both throw sl::Error as prepare() would.
    virtual std::unique_ptr<FrameWork> cpu_update(const Scene& scene,
                                                  const SceneChange& change) const = 0;
    virtual void apply_update(const Scene& scene, const SceneChange& change,
                              std::unique_ptr<FrameWork> work) = 0;
    // Both halves in turn (the serial mode).
    void update(const Scene& scene, const SceneChange& change) {
        apply_update(scene, change, cpu_update(scene, change));
    }
    // Adds I_s (linear RGB, alpha ignored) into the bound framebuffer, which is cleared to zero
    // and has no depth attachment; the viewport covers it.
    virtual void render(const VolumeInputs& inputs) = 0;
    // Counters of the last frame rendered (empty by default); may wait for the GPU.
    virtual MethodStatistics statistics() const { return {}; }
    // The method's own textures of the last frame (render targets, lookup tables).
    virtual gl::TextureViews textures() const { return {}; }
    // The shadow map the method asks for: `frame` with the filter and the size replaced by the
    // method's `shadow` and `shadow_size` parameters, each where it declared it.
    ShadowSettings shadow_settings(ShadowSettings frame) const;
    bool has_parameter(const std::string& name) const;

protected:
    void declare(Parameter parameter);
    // Shorthands of declare() for the two typed kinds.
    void declare_flag(std::string name, bool default_value, std::string description);
    void declare_choice(std::string name, std::vector<std::string> choices, size_t default_index,
                        std::string description);
    // Declares `shadow` (hard, pcf, vsm; `filter` by default) and `shadow_size`, read by
    // shadow_settings().
    void declare_shadow_parameters(ShadowFilter filter = ShadowFilter::pcf);

private:
    size_t choice_index(const std::string& name) const;
    const Parameter& typed(const std::string& name, std::initializer_list<Parameter::Type> types,
                           const char* reader) const;

    std::vector<Parameter> parameters_;
};

// `none`: no participating medium is rendered, I_s = 0; the frame is the surfaces alone
// (I_obj·T(Z)). The baseline every method's cost is measured against.
std::unique_ptr<VolumeMethod> create_no_volume();

}  // namespace sl::frame
