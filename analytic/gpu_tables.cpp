#include "analytic/gpu_tables.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "analytic/phase_functions.h"
#include "analytic/quadrature.h"

namespace sl::analytic {

using gl::GL;
using gl::Texture;

Texture create_sun_table() {
    // 1024² keeps bilinear interpolation within 1e-4 of the closed form (tested); the data is
    // computed once per process.
    constexpr int kSize = 1024;
    constexpr double kUMax = 32.0;  // SUN_TABLE_U_MAX in in_scattering.glsl
    static const std::vector<float> table = [] {
        std::vector<float> values(size_t(kSize) * kSize);
        for (int iu = 0; iu < kSize; ++iu) {
            const double u = kUMax * iu / (kSize - 1);
            double previous_v = 0.0, sum = 0.0;
            for (int iv = 0; iv < kSize; ++iv) {
                const double v = 0.5 * std::numbers::pi * iv / (kSize - 1);
                sum += integrate([&](double z) { return std::exp(-u * std::tan(z)); }, previous_v,
                                 std::min(v, 0.5 * std::numbers::pi - 1e-12));
                previous_v = v;
                values[size_t(iv) * kSize + iu] = float(sum);
            }
        }
        return values;
    }();
    Texture texture = gl::create_texture_2d(GL_R32F, kSize, kSize, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, kSize, GL_RED, GL_FLOAT, table.data());
    return texture;
}

Texture create_phase_table(const Medium& medium) {
    constexpr int kSize = 1024;  // PHASE_TABLE_SIZE in in_scattering.glsl
    std::vector<float> table(kSize);
    double sum = 0.0, previous = -0.5 * std::numbers::pi;
    for (int i = 0; i < kSize; ++i) {
        const double theta = std::numbers::pi * (double(i) / (kSize - 1) - 0.5);
        sum += integrate([&](double t) { return phase(medium.phase, medium.g, -std::sin(t)); },
                         previous, theta);
        previous = theta;
        table[size_t(i)] = float(sum);
    }
    Texture texture = gl::create_texture_2d(GL_R32F, kSize, 1, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, kSize, 1, GL_RED, GL_FLOAT, table.data());
    return texture;
}

}  // namespace sl::analytic
