#pragma once
// The interface every volumetric method implements (DESIGN.md §3): given the scene and the
// frame's buffers, add the in-scattered radiance I_s of Nilsson eq. 2.7 into the bound target.
// The renderer, the harness and the viewer talk to methods only through this interface; methods
// are created by name from the registry in methods/.

#include <memory>
#include <string>
#include <vector>

#include "gl/functions.h"
#include "gl/objects.h"
#include "gl/shaders/frame_uniforms.h"
#include "scenes/scene.h"

namespace sl::gl {

struct VolumeInputs {
    const Scene& scene;
    const shared::FrameUniforms& uniforms;  // also bound as the uniform block at its binding
    GLuint surface_depth;                   // camera depth buffer (depth texture)
    GLuint shadow_map;                      // light depth buffer (depth texture, compare mode)
    int width;
    int height;
};

// A parameter a method declares (Mitsuba style: documented where it is read), settable from the
// command line (`--set name=value`), configs and the viewer.
struct Parameter {
    enum class Type { integer, real };
    std::string name;
    Type type = Type::real;
    double value = 0.0;
    double default_value = 0.0;
    double min = 0.0;
    double max = 0.0;
    std::string description;
};

class VolumeMethod {
public:
    virtual ~VolumeMethod() = default;
    const std::vector<Parameter>& parameters() const { return parameters_; }
    double parameter(const std::string& name) const;
    // Parses and sets one parameter; throws sl::Error naming the method and the parameter when
    // the name is unknown, the text is not a number of its type, or it is out of range.
    void set(const std::string& name, const std::string& text);
    virtual std::string name() const = 0;
    // Called once per scene before the first frame (CPU work such as building regions).
    virtual void prepare(const Scene& scene) = 0;
    // Adds I_s (linear RGB, alpha ignored) into the bound framebuffer, which is cleared to zero
    // and has no depth attachment; the viewport covers it.
    virtual void render(const VolumeInputs& inputs) = 0;

protected:
    void declare(Parameter parameter);

private:
    std::vector<Parameter> parameters_;
};

}  // namespace sl::gl

namespace sl::methods {

// The registry (methods/volume_methods.cpp): the methods that exist, in display order.
std::vector<std::string> volume_method_names();
// Throws sl::Error naming the known methods when `name` is not one of them.
std::unique_ptr<gl::VolumeMethod> create_volume_method(const std::string& name);

// Sun et al. 2005's F(u, v) = ∫_0^v exp(-u tan ζ) dζ on u in [0, 32], v in [0, π/2], 1024², for
// gl/shaders/in_scattering.glsl's `sun_table` at texture unit kSunTableUnit.
constexpr GLuint kSunTableUnit = 7;
gl::Texture create_sun_table();
// P(θ) = ∫_{-π/2}^θ p(-sin t) dt for the medium's phase function, 1024 samples over
// θ in [-π/2, π/2], for in_scattering.glsl's `phase_table` at texture unit kPhaseTableUnit.
constexpr GLuint kPhaseTableUnit = 6;
gl::Texture create_phase_table(const Medium& medium);

}  // namespace sl::methods
