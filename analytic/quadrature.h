#pragma once
// Globally adaptive Gauss–Kronrod (7/15) quadrature (as QUADPACK's QAG): the numerical oracle the
// closed forms are tested against, and the fallback where no closed form exists. The interval
// with the largest error estimate is bisected until the summed estimate meets the tolerance or
// the interval budget is spent.

#include <algorithm>
#include <cmath>
#include <queue>
#include <vector>

namespace sl::analytic {

namespace detail {

// Nodes and weights of the 15-point Kronrod rule and its embedded 7-point Gauss rule on [-1, 1].
inline constexpr double kKronrodNodes[8] = {
    0.991455371120812639, 0.949107912342758525, 0.864864423359769073, 0.741531185599394440,
    0.586087235467691130, 0.405845151377397167, 0.207784955007898468, 0.000000000000000000};
inline constexpr double kKronrodWeights[8] = {
    0.022935322010529225, 0.063092092629978553, 0.104790010322250184, 0.140653259715525919,
    0.169004726639267903, 0.190350578064785410, 0.204432940075298892, 0.209482141084727828};
inline constexpr double kGaussWeights[4] = {0.129484966168869693, 0.279705391489276668,
                                            0.381830050505118945, 0.417959183673469388};

struct Piece {
    double a, b, value, error;
    bool operator<(const Piece& other) const { return error < other.error; }
};

template <typename F>
Piece kronrod(const F& f, double a, double b) {
    const double center = 0.5 * (a + b), half = 0.5 * (b - a);
    const double f_center = f(center);
    double k = kKronrodWeights[7] * f_center;
    double g = kGaussWeights[3] * f_center;
    for (int i = 0; i < 7; ++i) {
        const double x = half * kKronrodNodes[i];
        const double sum = f(center - x) + f(center + x);
        k += kKronrodWeights[i] * sum;
        if (i % 2 == 1) {
            g += kGaussWeights[i / 2] * sum;
        }
    }
    return {a, b, k * half, std::abs((k - g) * half)};
}

}  // namespace detail

// ∫_a^b f(x) dx to max(absolute, relative × |result|), using at most `max_pieces` intervals.
template <typename F>
double integrate(const F& f, double a, double b, double relative = 1e-12, double absolute = 1e-300,
                 int max_pieces = 4000) {
    if (a == b) {
        return 0.0;
    }
    std::priority_queue<detail::Piece> pieces;
    pieces.push(detail::kronrod(f, a, b));
    double value = pieces.top().value, error = pieces.top().error;
    while (error > std::max(absolute, relative * std::abs(value)) &&
           int(pieces.size()) < max_pieces) {
        const detail::Piece worst = pieces.top();
        pieces.pop();
        const double middle = 0.5 * (worst.a + worst.b);
        const detail::Piece left = detail::kronrod(f, worst.a, middle);
        const detail::Piece right = detail::kronrod(f, middle, worst.b);
        value += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        pieces.push(left);
        pieces.push(right);
    }
    return value;
}

}  // namespace sl::analytic
