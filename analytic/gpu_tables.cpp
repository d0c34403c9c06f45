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

// Column x of the physical table's first channel: H(s_x, v) cumulatively over v.
void physical_column(const Medium& medium, int size, int x, float* values) {
    const double s = double(x) / (size - 1);
    const double p_forward = phase(medium.phase, medium.g, 1.0);
    const double step = 0.5 * kPi / (size - 1);
    values[2 * size_t(x)] = 0.0f;
    if (x == size - 1) {
        for (int y = 1; y < size; ++y)
            values[2 * (size_t(y) * size + x)] = float(p_forward);  // u = ∞
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
        values[2 * (size_t(y) * size + x)] = float((1.0 + u) * sum);
    }
}

// The physical table's second channel, the tail T(a, b) = s (1 + s) e^s K(a s, s) with
// K(u, s) = ∫_s^∞ e^(-s') p(c(u, s')) / (u² + s'²) ds', c = (u² - s'²) / (u² + s'²), on
// x = sqrt(a) (a backward peak of p lies at small a, 1 + c = 2a² / (1 + a²)) and y = b,
// s = b² / (1 - b²) (in_scattering.h derives it). Every entry is its own integral; they are
// computed in two regimes:
//   s <= 1: s' = s e^y, T = (1 + s) ∫_0^∞ e^(-s (e^y - 1)) P_a(y) dy with
//           P_a(y) = p(c) e^y / (a² + e^(2y)), c = (a² - e^(2y)) / (a² + e^(2y)). The phase part
//           P_a is the column's and the exponential the row's, so on one fixed node set in y the
//           whole block is a matrix product (7 nodes every 0.25 in y up to y = 24, where
//           e^-y < 4e-11: the integrand decays at least as fast as e^-y).
//   s > 1:  s' = s + t, T = s (1 + s) ∫_0^∞ e^(-t) p(c) / (a² s² + (s + t)²) dt, Gauss-Legendre
//           (7 points) on pieces that widen with t, to t = 28 (e^-28 < 7e-13).
//   b = 1:  s = ∞, T = p(c∞) / (1 + a²), c∞ = (a² - 1) / (a² + 1).
void physical_tail(const Medium& medium, int size, float* values) {
    static constexpr double kNodes7[7] = {
        -0.949107912342758525, -0.741531185599394440, -0.405845151377397167, 0.0,
        0.405845151377397167,  0.741531185599394440,  0.949107912342758525};
    static constexpr double kWeights7[7] = {
        0.129484966168869693, 0.279705391489276668, 0.381830050505118945, 0.417959183673469388,
        0.381830050505118945, 0.279705391489276668, 0.129484966168869693};
    auto p = [&](double cos_alpha) { return phase(medium.phase, medium.g, cos_alpha); };
    auto row_s = [&](int y) {
        const double b = double(y) / (size - 1);
        return b * b / (1.0 - b * b);
    };
    auto at = [&](int x, int y) -> float& { return values[2 * (size_t(y) * size + x) + 1]; };
    // The y nodes of the small-s regime: Gauss-Legendre (7 points) on pieces 0.25 wide.
    constexpr double kPiece = 0.25, kEnd = 24.0;
    std::vector<double> node_y, node_w;
    for (double start = 0.0; start < kEnd - 1e-9; start += kPiece) {
        for (int k = 0; k < 7; ++k) {
            node_y.push_back(start + 0.5 * kPiece * (1.0 + kNodes7[k]));
            node_w.push_back(0.5 * kPiece * kWeights7[k]);
        }
    }
    const size_t nodes = node_y.size();
    int small_rows = 0;
    while (small_rows < size - 1 && row_s(small_rows) <= 1.0)
        ++small_rows;
    // E[y][k] = w_k e^(-s_y (e^(y_k) - 1)), the rows' exponentials.
    std::vector<double> exponential(size_t(small_rows) * nodes);
    tbb::parallel_for(0, small_rows, [&](int y) {
        const double s = row_s(y);
        for (size_t k = 0; k < nodes; ++k)
            exponential[size_t(y) * nodes + k] = node_w[k] * std::exp(-s * std::expm1(node_y[k]));
    });
    tbb::parallel_for(0, size, [&](int x) {
        const double root_a = double(x) / (size - 1), a = root_a * root_a, a2 = a * a;
        std::vector<double> column(nodes);
        for (size_t k = 0; k < nodes; ++k) {
            const double e = std::exp(node_y[k]), e2 = e * e;
            column[k] = p((a2 - e2) / (a2 + e2)) * e / (a2 + e2);
        }
        for (int y = 0; y < small_rows; ++y) {
            const double* row = &exponential[size_t(y) * nodes];
            double sum = 0.0;
            for (size_t k = 0; k < nodes; ++k)
                sum += row[k] * column[k];
            at(x, y) = float((1.0 + row_s(y)) * sum);
        }
        static constexpr double kEdges[] = {0.0, 0.5, 1.0, 2.0, 3.5, 6.0, 10.0, 16.0, 28.0};
        for (int y = small_rows; y < size - 1; ++y) {
            const double s = row_s(y), u2 = a2 * s * s;
            double sum = 0.0;
            for (size_t piece = 0; piece + 1 < std::size(kEdges); ++piece) {
                const double lo = kEdges[piece], half = 0.5 * (kEdges[piece + 1] - lo);
                for (int k = 0; k < 7; ++k) {
                    const double t = lo + half * (1.0 + kNodes7[k]), q = (s + t) * (s + t);
                    sum += half * kWeights7[k] * std::exp(-t) * p((u2 - q) / (u2 + q)) / (u2 + q);
                }
            }
            at(x, y) = float(s * (1.0 + s) * sum);
        }
        at(x, size - 1) = float(p((a2 - 1.0) / (a2 + 1.0)) / (1.0 + a2));
    });
}

// Column x of the simplified table: R(κ_x, β) cumulatively over β in the first channel, and its
// complement ∫_β^{π/2} in the second, stored flipped (row y at β = π/2 - y step) so that a
// ray's far end, where β -> π/2, reads it at a small, exact coordinate.
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
    std::vector<double> cumulative(size_t(size), 0.0);
    for (int y = 1; y < size; ++y) {
        const double a = -0.5 * kPi + step * (y - 1), b = -0.5 * kPi + step * y;
        cumulative[y] =
            cumulative[y - 1] + (a < 0.0 && b > 0.0 ? piece(a, 0.0) + piece(0.0, b) : piece(a, b));
    }
    // The complement summed from the far end, so that its small values keep their digits.
    std::vector<double> complement(size_t(size), 0.0);
    for (int y = size - 2; y >= 0; --y)
        complement[y] = complement[y + 1] + (cumulative[y + 1] - cumulative[y]);
    for (int y = 0; y < size; ++y) {
        values[2 * (size_t(y) * size + x)] = float(cumulative[y]);
        values[2 * (size_t(size - 1 - y) * size + x) + 1] = float(complement[y]);
    }
}

std::shared_ptr<const MediumTable> build(const Medium& medium, int size) {
    const auto start = std::chrono::steady_clock::now();
    auto table = std::make_shared<MediumTable>();
    table->size = size;
    table->values.assign(2 * size_t(size) * size, 0.0f);
    const bool physical = medium.model == MediumModel::physical;
    // Columns are independent: spread them over the cores.
    tbb::parallel_for(0, size, [&](int x) {
        if (physical)
            physical_column(medium, size, x, table->values.data());
        else
            simplified_column(medium, size, x, table->values.data());
    });
    if (physical)
        physical_tail(medium, size, table->values.data());
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
    Texture texture = gl::create_texture_2d(GL_RG32F, size, size, GL_NEAREST);
    GL.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    GL.TextureSubImage2D(texture.id(), 0, 0, 0, size, size, GL_RG, GL_FLOAT, table->values.data());
    return texture;
}

}  // namespace sl::analytic
