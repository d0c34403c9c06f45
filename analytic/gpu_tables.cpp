#include "analytic/gpu_tables.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>

#include <tbb/parallel_for.h>

#include "analytic/in_scattering.h"
#include "analytic/phase_functions.h"

namespace sl::analytic {

using gl::GL;
using gl::Texture;

namespace {

constexpr double kPi = std::numbers::pi;

// ∫_a^b f by 3-point Gauss-Legendre on `pieces` equal sub-intervals.
template <typename F>
double gauss3(const F& f, double a, double b, int pieces) {
    static constexpr double kNode = 0.774596669241483377, kOuter = 5.0 / 9.0, kInner = 8.0 / 9.0;
    const double h = (b - a) / pieces;
    double sum = 0.0;
    for (int k = 0; k < pieces; ++k) {
        const double c = a + (k + 0.5) * h, r = 0.5 * h * kNode;
        sum += kOuter * (f(c - r) + f(c + r)) + kInner * f(c);
    }
    return 0.5 * h * sum;
}

// Column x of the physical table: H(s_x, v) cumulatively over v.
void physical_column(const Medium& medium, int size, int x, float* values) {
    const double s = double(x) / (size - 1);
    const double p_forward = phase(medium.phase, medium.g, 1.0);
    const double step = 0.5 * kPi / (size - 1);
    values[x] = 0.0f;
    if (x == size - 1) {
        for (int y = 1; y < size; ++y)
            values[size_t(y) * size + x] = float(p_forward);  // u = ∞
        return;
    }
    const double u = s / (1.0 - s);
    auto f = [&](double zeta) {
        return std::exp(-u * std::tan(zeta)) * phase(medium.phase, medium.g, std::cos(2.0 * zeta));
    };
    double sum = 0.0;
    for (int y = 1; y < size; ++y) {
        const double a = step * (y - 1), b = std::min(step * y, 0.5 * kPi);
        // The exponential decays at the rate u sec² ζ: a few Gauss points per decay length.
        const double c = std::cos(b);
        const double rate = u * step / std::max(c * c, 1e-12);
        const int pieces = int(std::clamp(std::ceil(4.0 * rate), 1.0, 32.0));
        sum += gauss3(f, a, b, pieces);
        values[size_t(y) * size + x] = float((1.0 + u) * sum);
    }
}

// Column x of the simplified table: R(κ_x, β) cumulatively over β.
void simplified_column(const Medium& medium, int size, int x, float* values) {
    const double kappa = double(x) / (size - 1);
    const double step = kPi / (size - 1);
    auto f = [&](double beta) {
        return phase(medium.phase, medium.g, simplified_cos_alpha(kappa, beta));
    };
    // cos α turns from +1 to -1 over |β| of about κ around β = 0: split there, and resolve it.
    auto piece = [&](double a, double b) {
        const double scale = std::max(kappa, std::min(std::abs(a), std::abs(b)));
        const int pieces =
            int(std::clamp(std::ceil(4.0 * (b - a) / std::max(scale, 1e-9)), 1.0, 64.0));
        return gauss3(f, a, b, pieces);
    };
    double sum = 0.0;
    values[x] = 0.0f;
    for (int y = 1; y < size; ++y) {
        const double a = -0.5 * kPi + step * (y - 1), b = -0.5 * kPi + step * y;
        sum += a < 0.0 && b > 0.0 ? piece(a, 0.0) + piece(0.0, b) : piece(a, b);
        values[size_t(y) * size + x] = float(sum);
    }
}

std::shared_ptr<const MediumTable> build(const Medium& medium, int size) {
    const auto start = std::chrono::steady_clock::now();
    auto table = std::make_shared<MediumTable>();
    table->size = size;
    table->values.assign(size_t(size) * size, 0.0f);
    const bool physical = medium.model == MediumModel::physical;
    // Columns are independent: spread them over the cores.
    tbb::parallel_for(0, size, [&](int x) {
        if (physical)
            physical_column(medium, size, x, table->values.data());
        else
            simplified_column(medium, size, x, table->values.data());
    });
    table->build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return table;
}

}  // namespace

std::shared_ptr<const MediumTable> medium_table(const Medium& medium, int size) {
    using Key = std::tuple<int, int, float, int>;
    const Key key{int(medium.model), int(medium.phase),
                  uses_asymmetry(medium.phase) ? medium.g : 0.0f, size};
    static std::mutex mutex;
    static std::map<Key, std::shared_ptr<const MediumTable>> cache;
    const std::lock_guard lock(mutex);
    if (cache.size() >= 8 && !cache.contains(key)) {
        cache.clear();  // a viewer dragging g would otherwise keep every table it passed
    }
    auto& slot = cache[key];
    if (!slot) {
        slot = build(medium, size);
    }
    return slot;
}

Texture create_medium_table(const Medium& medium, int size) {
    const std::shared_ptr<const MediumTable> table = medium_table(medium, size);
    Texture texture = gl::create_texture_2d(GL_R32F, size, size, GL_LINEAR);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, size, size, GL_RED, GL_FLOAT, table->values.data());
    return texture;
}

}  // namespace sl::analytic
