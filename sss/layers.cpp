#include "sss/layers.h"

#include <complex>
#include <memory>

#include <fftw3.h>

#include "core/error.h"

namespace sl::sss {

namespace {

using complex = std::complex<double>;

struct FftwFree {
    void operator()(void* p) const { fftw_free(p); }
};
struct PlanDestroy {
    void operator()(fftw_plan_s* p) const { fftw_destroy_plan(p); }
};
using Plan = std::unique_ptr<fftw_plan_s, PlanDestroy>;

// The frequency-domain transforms of one grid size: F(f) = h² DFT(f) approximates the continuous
// Fourier transform, so F(0) = ∫ f dA.
class Transform {
public:
    Transform(int padded, double spacing)
        : n_(padded),
          h_(spacing),
          real_(static_cast<double*>(fftw_malloc(sizeof(double) * size_t(n_ * n_)))),
          spectrum_(static_cast<fftw_complex*>(
              fftw_malloc(sizeof(fftw_complex) * size_t(n_ * (n_ / 2 + 1))))) {
        forward_.reset(fftw_plan_dft_r2c_2d(n_, n_, real_.get(), spectrum_.get(), FFTW_ESTIMATE));
        backward_.reset(fftw_plan_dft_c2r_2d(n_, n_, spectrum_.get(), real_.get(), FFTW_ESTIMATE));
    }
    size_t spectrum_size() const { return size_t(n_ * (n_ / 2 + 1)); }

    // f sampled at the lattice points (wrapped around the origin), zero beyond `support`.
    std::vector<complex> forward(const std::function<double(double)>& f, int support) {
        for (int y = 0; y < n_; ++y) {
            const int sy = y < n_ / 2 ? y : y - n_;
            for (int x = 0; x < n_; ++x) {
                const int sx = x < n_ / 2 ? x : x - n_;
                const bool inside = std::abs(sx) < support && std::abs(sy) < support;
                real_.get()[y * n_ + x] =
                    inside ? f(h_ * std::sqrt(double(sx * sx + sy * sy))) : 0.0;
            }
        }
        fftw_execute(forward_.get());
        std::vector<complex> out(spectrum_size());
        for (size_t i = 0; i < out.size(); ++i) {
            out[i] = h_ * h_ * complex(spectrum_.get()[i][0], spectrum_.get()[i][1]);
        }
        return out;
    }
    // The values along +x at k = 0 .. count − 1 of the inverse transform.
    std::vector<double> inverse(const std::vector<complex>& spectrum, int count) {
        for (size_t i = 0; i < spectrum.size(); ++i) {
            spectrum_.get()[i][0] = spectrum[i].real();
            spectrum_.get()[i][1] = spectrum[i].imag();
        }
        fftw_execute(backward_.get());  // unnormalised: n² times the inverse DFT
        const double scale = 1.0 / (double(n_) * n_ * h_ * h_);
        std::vector<double> out(static_cast<size_t>(count));
        for (int k = 0; k < count; ++k) {
            out[size_t(k)] = real_.get()[k] * scale;
        }
        return out;
    }

private:
    int n_;
    double h_;
    std::unique_ptr<double, FftwFree> real_;
    std::unique_ptr<fftw_complex, FftwFree> spectrum_;
    Plan forward_, backward_;
};

}  // namespace

CombinedLayers combine_layers(const std::vector<LayerFunctions>& layers, double extent_mm,
                              int grid) {
    if (layers.empty()) {
        fail("layered material: no layers");
    }
    if (grid < 8 || grid % 2 != 0 || !(extent_mm > 0.0)) {
        fail("layered material: the grid must be even and at least 8, the extent > 0");
    }
    const double h = 2.0 * extent_mm / grid;
    // Zero padding to twice the grid: one convolution of two supports fits without wrapping.
    Transform fft(2 * grid, h);
    std::vector<complex> R = fft.forward(layers[0].R, grid / 2);
    std::vector<complex> T = fft.forward(layers[0].T, grid / 2);
    for (size_t l = 1; l < layers.size(); ++l) {
        const std::vector<complex> R2 = fft.forward(layers[l].R, grid / 2);
        const std::vector<complex> T2 = fft.forward(layers[l].T, grid / 2);
        for (size_t i = 0; i < R.size(); ++i) {
            const complex denominator = 1.0 - R2[i] * R[i];
            const complex t12 = T[i] * T2[i] / denominator;                // eq. 3.10
            const complex r12 = R[i] + T[i] * R2[i] * T[i] / denominator;  // eq. 3.12
            R[i] = r12;
            T[i] = t12;
        }
    }
    CombinedLayers out;
    out.spacing = h;
    out.total_R = R[0].real();
    out.total_T = T[0].real();
    out.R = fft.inverse(R, grid / 2);
    out.T = fft.inverse(T, grid / 2);
    return out;
}

LayeredProfile layered_profile(const std::vector<Layer>& layers, double extent_mm, int grid,
                               int texels, int pairs) {
    if (texels < 2) {
        fail("layered material: the profile needs at least 2 texels");
    }
    LayeredProfile out;
    out.reflectance.r_max = extent_mm;
    out.reflectance.texels.assign(size_t(texels), glm::vec3(0.0f));
    for (int c = 0; c < 3; ++c) {
        std::vector<LayerFunctions> functions;
        for (const Layer& layer : layers) {
            if (!(layer.thickness_mm >= 0.0) || !std::isfinite(layer.thickness_mm)) {
                fail("layered material: layer '{}' has a bad thickness {}", layer.material.name,
                     layer.thickness_mm);
            }
            const Diffusion d = RgbDiffusion::of(layer.material)[c];
            if (layer.thickness_mm == 0.0) {  // semi-infinite: the dipole, nothing through
                functions.push_back(
                    {[d](double r) { return dipole_rd(r, d); }, [](double) { return 0.0; }});
            } else {
                const double t = layer.thickness_mm;
                functions.push_back(
                    {[d, t, pairs](double r) { return multipole(r, t, d, pairs).R; },
                     [d, t, pairs](double r) { return multipole(r, t, d, pairs).T; }});
            }
        }
        const CombinedLayers combined = combine_layers(functions, extent_mm, grid);
        out.total_R[c] = combined.total_R;
        out.total_T[c] = combined.total_T;
        // Resample the radial values onto the texels (linear), last texel zero.
        for (int i = 0; i + 1 < texels; ++i) {
            const double s = (extent_mm * i / (texels - 1)) / combined.spacing;
            const size_t k = std::min(size_t(s), combined.R.size() - 2);
            const double t = std::min(s - double(k), 1.0);
            out.reflectance.texels[size_t(i)][c] =
                float(std::max(0.0, combined.R[k] * (1 - t) + combined.R[k + 1] * t));
        }
    }
    return out;
}

}  // namespace sl::sss
