// The suite every registered method passes (methods/registry.h): a method gets these tests by
// being in the registry, with nothing to write (docs/adding-a-method.md). Each checks a property
// of the VolumeMethod contract (frame/volume_method.h), not of one method's algorithm:
//   - its parameters read back by name, and refuse what lies outside their kind, by name;
//   - finite, non-negative I_s with the eye inside the light and the light behind the eye;
//   - every texture it shows the previewer is a real 2D texture;
//   - its per-frame update leaves it as a fresh prepare() of the new scene would.
// Each method's own tests (tests/<folder>_*_test.cpp) check its algorithm against its oracles.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "core/error.h"
#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "methods/registry.h"
#include "scenes/animation.h"
#include "tests/support.h"

namespace sl::test {
namespace {

using frame::Parameter;

class EveryMethod : public ::testing::TestWithParam<std::string> {
protected:
    void SetUp() override { headless_gl(); }
    std::unique_ptr<frame::VolumeMethod> create() const {
        return methods::create_volume_method(GetParam());
    }
};

// The message of the sl::Error that `action` throws; a test failure when it throws none.
template <class Action>
std::string refusal(Action&& action) {
    try {
        action();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "accepted";
    return "";
}

// Each parameter's value written by name (Parameter::text) reads back to the same value; a value
// outside the parameter's kind is refused with a message naming the method and the parameter
// (and, for a choice, every choice); an unknown name is refused naming the ones the method has.
TEST_P(EveryMethod, ParametersReadBackByNameAndRefuseWhatLiesOutsideTheirKind) {
    const auto method = create();
    for (const Parameter& p : method->parameters()) {
        SCOPED_TRACE(p.name);
        method->set(p.name, p.text());
        EXPECT_EQ(method->find(p.name).value, p.value);
        const auto refused = [&](const std::string& value) {
            const std::string message = refusal([&] { method->set(p.name, value); });
            EXPECT_NE(message.find(GetParam()), std::string::npos) << message;
            EXPECT_NE(message.find(p.name), std::string::npos) << message;
            EXPECT_EQ(method->find(p.name).value, p.value) << "a refused value was kept";
            return message;
        };
        switch (p.type) {
            case Parameter::Type::integer:
                refused("1.5");
                [[fallthrough]];
            case Parameter::Type::real:
                refused("nan");
                refused("");
                refused(fmt::format("{}", p.max * 2.0 + 1.0));
                refused(fmt::format("{}", p.min - 1.0 - std::abs(p.min)));
                break;
            case Parameter::Type::boolean: {
                EXPECT_NE(refused("maybe").find("true or false"), std::string::npos);
                method->set(p.name, "true");
                EXPECT_TRUE(method->flag(p.name));
                method->set(p.name, "0");  // the numeric flags' old spelling
                EXPECT_FALSE(method->flag(p.name));
                method->set(p.name, p.text());
                break;
            }
            case Parameter::Type::choice: {
                const std::string message = refused("no-such-choice");
                for (const std::string& choice : p.choices) {
                    EXPECT_NE(message.find(choice), std::string::npos) << message;
                    method->set(p.name, choice);
                    EXPECT_EQ(method->choice_name(p.name), choice);
                }
                method->set(p.name, p.text());
                break;
            }
        }
    }
    const std::string unknown = refusal([&] { method->set("no_such_parameter", "1"); });
    for (const Parameter& p : method->parameters()) {
        EXPECT_NE(unknown.find(p.name), std::string::npos) << unknown;
    }
}

// The eye inside the light (looking across the beam and down at the objects) and the light
// behind the eye (support.h's eye_and_light_views): every pixel of I_s finite and non-negative,
// and some light scattered (but by `none`, which renders no medium).
TEST_P(EveryMethod, FiniteOutputWithTheEyeInsideTheLightAndTheLightBehindTheEye) {
    for (const auto& [view, scene] : eye_and_light_views()) {
        const frame::Frame frame = render_method(scene, GetParam(), 64, 36);
        double sum = 0.0;
        for (const float v : frame.in_scattering.rgb) {
            ASSERT_TRUE(std::isfinite(v)) << view;
            ASSERT_GE(v, 0.0f) << view;
            sum += v;
        }
        if (GetParam() != "none") {
            EXPECT_GT(sum, 0.0) << view;
        }
    }
}

// What the method shows the buffer previewer, asked for after one frame and made by the next:
// named "<method>/<what>", each a live 2D texture with a size.
TEST_P(EveryMethod, PreviewerTexturesAreLiveTextures) {
    const Scene scene = boxes_scene(MediumModel::physical);
    frame::SceneRenderer renderer(scene, {.width = 64, .height = 36});
    const auto method = create();
    method->prepare(scene);
    renderer.draw(*method);
    method->textures();
    renderer.draw(*method);
    for (const gl::TextureView& view : method->textures()) {
        SCOPED_TRACE(view.name);
        EXPECT_EQ(view.name.rfind(GetParam() + "/", 0), 0u);
        ASSERT_TRUE(gl::GL.IsTexture(view.texture));
        GLint width = 0, height = 0;
        gl::GL.GetTextureLevelParameteriv(view.texture, 0, GL_TEXTURE_WIDTH, &width);
        gl::GL.GetTextureLevelParameteriv(view.texture, 0, GL_TEXTURE_HEIGHT, &height);
        EXPECT_GT(width, 0);
        EXPECT_GT(height, 0);
    }
}

// Prepared on one scene and updated to another (the light moved and turned, an object moved, the
// camera moved), the method draws what a fresh prepare() of the second scene draws.
TEST_P(EveryMethod, UpdateToAChangedSceneEqualsAFreshPrepare) {
    const Scene before = boxes_scene(MediumModel::physical);
    Scene after = before;
    after.light.position += glm::vec3(-0.6f, 0.3f, 0.4f);
    after.light.target += glm::vec3(0.3f, 0.0f, -0.2f);
    after.objects[1].transform =
        glm::translate(glm::mat4(1.0f), glm::vec3(0.4f, 0.0f, 0.3f)) * after.objects[1].transform;
    after.camera.position += glm::vec3(0.5f, -0.2f, 0.3f);
    const SceneChange change = scene_change(before, after);
    ASSERT_TRUE(change.light_geometry && change.camera && !change.objects.empty());

    const auto updated = create();
    {
        frame::SceneRenderer renderer(before, {.width = 64, .height = 36});
        updated->prepare(before);
        renderer.draw(*updated);
    }
    frame::SceneRenderer renderer(after, {.width = 64, .height = 36});
    updated->update(after, change);
    renderer.draw(*updated);
    const Image moved = renderer.read_in_scattering();

    const auto fresh = create();
    fresh->prepare(after);
    renderer.draw(*fresh);
    const Image expected = renderer.read_in_scattering();
    EXPECT_LE(max_abs_difference(moved, expected), 1e-5 * (1.0 + image_peak(expected)));
}

INSTANTIATE_TEST_SUITE_P(Registry, EveryMethod, ::testing::ValuesIn(methods::volume_method_names()),
                         [](const ::testing::TestParamInfo<std::string>& method) {
                             return method.param;
                         });

}  // namespace
}  // namespace sl::test
