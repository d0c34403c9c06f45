#include "beamtree/region_picture.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace sl::bt {

namespace {

using glm::dvec3;

// A pixel's eye ray from the near plane to its first surface, clipped to the influence pyramid,
// with the regions along it (t in metres from the near-plane point).
struct PixelRegions {
    bool inside = false;  // the ray meets the influence pyramid
    double end = 0.0;     // the clipped segment's far end
    std::vector<RegionInterval> intervals;
};

PixelRegions trace_pixel(const BeamTree& tree, const PixelUnprojector& pixels,
                         std::span<const float> depth_buffer, int width, int x, int y) {
    PixelRegions result;
    const double depth = 2.0 * double(depth_buffer[size_t(y) * width + x]) - 1.0;
    const dvec3 origin = pixels.point(x, y, -1.0);
    const dvec3 end = pixels.point(x, y, std::min(depth, 1.0));
    double t0 = 0.0, t1 = 1.0;
    for (const Plane& plane : tree.influence_planes()) {
        const double d0 = plane.distance(origin), d1 = plane.distance(end);
        if (d0 > 0.0 && d1 > 0.0) {
            return result;
        }
        if (d0 > 0.0)
            t0 = std::max(t0, d0 / (d0 - d1));
        if (d1 > 0.0)
            t1 = std::min(t1, d0 / (d0 - d1));
    }
    const double length = glm::length(end - origin);
    if (t1 <= t0 || !(length > 0.0)) {
        return result;
    }
    result.inside = true;
    result.end = t1 * length;
    tree.trace(origin, (end - origin) / length, t0 * length, t1 * length, result.intervals);
    return result;
}

// Whether the traced neighbours of an untraced pixel cross the same regions in the same order,
// ending within 1% of each other: then the pixel takes their mean and needs no ray of its own.
bool alike(const std::vector<const PixelRegions*>& neighbours) {
    const PixelRegions& first = *neighbours.front();
    for (const PixelRegions* n : neighbours) {
        if (n->inside != first.inside || n->intervals.size() != first.intervals.size() ||
            !(std::abs(n->end - first.end) <= 0.01 * first.end)) {
            return false;
        }
        for (size_t k = 0; k < n->intervals.size(); ++k) {
            if (n->intervals[k].region != first.intervals[k].region) {
                return false;
            }
        }
    }
    return true;
}

// The neighbours' intervals, averaged bound by bound.
void mean_of(const std::vector<const PixelRegions*>& neighbours, PixelRegions& mean) {
    mean = *neighbours.front();
    for (size_t k = 0; k < mean.intervals.size(); ++k) {
        double begin = 0.0, end = 0.0;
        for (const PixelRegions* n : neighbours) {
            begin += n->intervals[k].begin;
            end += n->intervals[k].end;
        }
        mean.intervals[k].begin = begin / double(neighbours.size());
        mean.intervals[k].end = end / double(neighbours.size());
    }
}

// The regions as a coloured fog over one pixel: lit yellow, uncertain grey, unlit black.
// Uncertain and unlit absorb `shadow_weight` times more than lit (8 under a spot light) so that
// thin shadow volumes show through the lit air in front of them; `scale` is the length over which
// lit air reaches 78 % opacity.
void shade(const PixelRegions& regions, double scale, double shadow_weight, uint8_t* pixel) {
    const glm::dvec3 colors[3] = {{1.0, 0.82, 0.1}, {0.55, 0.55, 0.55}, {0.0, 0.0, 0.0}};
    const double extinction[3] = {1.5 / scale, 1.5 * shadow_weight / scale,
                                  1.5 * shadow_weight / scale};
    dvec3 color(0.0);
    double transparency = 1.0;
    for (const RegionInterval& interval : regions.intervals) {
        const auto region = size_t(interval.region);
        const double alpha = 1.0 - std::exp(-extinction[region] * (interval.end - interval.begin));
        color += transparency * alpha * colors[region];
        transparency *= 1.0 - alpha;
    }
    for (int c = 0; c < 3; ++c) {
        pixel[c] = static_cast<uint8_t>(
            std::lround(transparency * pixel[c] + 255.0 * std::min(1.0, color[c])));
    }
}

}  // namespace

std::vector<uint8_t> draw_regions(const Scene& scene, const BeamTree& tree,
                                  std::span<const float> depth, std::span<const uint8_t> srgb8,
                                  int width, int height) {
    if (depth.size() != size_t(width) * size_t(height) ||
        srgb8.size() != size_t(width) * size_t(height) * 3) {
        fail("draw_regions: a {}x{} picture needs {} depths and {} sRGB bytes, got {} and {}",
             width, height, size_t(width) * height, size_t(width) * height * 3, depth.size(),
             srgb8.size());
    }
    const PixelUnprojector pixels(scene.camera, width, height);
    // Every other pixel in x and y is traced; the rest take their traced neighbours' mean where
    // those agree, or are traced too.
    const int coarse_width = (width + 1) / 2, coarse_height = (height + 1) / 2;
    std::vector<PixelRegions> coarse(size_t(coarse_width) * coarse_height);
    tbb::parallel_for(0, coarse_height, [&](int j) {
        for (int i = 0; i < coarse_width; ++i) {
            coarse[size_t(j) * coarse_width + i] =
                trace_pixel(tree, pixels, depth, width, 2 * i, 2 * j);
        }
    });
    // The fog's length scale: a spot light's range; a sun's range is the depth of the scene's
    // whole box, which says nothing of what the camera sees, so there the longest stretch of the
    // influence along a traced eye ray (the house seen from inside: metres of a box tens deep).
    // A sun lights the scene but for its shadows, and a camera inside them (a room lit through
    // its windows) looks through metres of unlit air: there shadows absorb as lit air does, so
    // that the shafts show through them.
    double scale = double(scene.light.far), shadow_weight = 8.0;
    if (scene.light.parallel()) {
        shadow_weight = 1.0;
        double longest = 0.0;
        for (const PixelRegions& traced : coarse) {
            if (traced.inside && !traced.intervals.empty()) {
                longest = std::max(longest, traced.end - traced.intervals.front().begin);
            }
        }
        if (longest > 0.0) {
            scale = std::min(scale, longest);
        }
    }
    std::vector<uint8_t> image(srgb8.begin(), srgb8.end());
    tbb::parallel_for(0, height, [&](int y) {
        std::vector<const PixelRegions*> neighbours;
        PixelRegions mean, own;
        for (int x = 0; x < width; ++x) {
            neighbours.clear();
            for (const int cy : {y / 2, (y + 1) / 2}) {
                for (const int cx : {x / 2, (x + 1) / 2}) {
                    if (cx < coarse_width && cy < coarse_height) {
                        const PixelRegions* n = &coarse[size_t(cy) * coarse_width + cx];
                        if (std::find(neighbours.begin(), neighbours.end(), n) == neighbours.end())
                            neighbours.push_back(n);
                    }
                }
            }
            const bool traced = x % 2 == 0 && y % 2 == 0;
            const PixelRegions* regions = nullptr;
            if (traced) {
                regions = neighbours.front();
            } else if (neighbours.size() == size_t((x % 2 + 1) * (y % 2 + 1)) &&
                       alike(neighbours)) {
                mean_of(neighbours, mean);
                regions = &mean;
            } else {
                own = trace_pixel(tree, pixels, depth, width, x, y);
                regions = &own;
            }
            if (regions->inside) {
                shade(*regions, scale, shadow_weight, &image[(size_t(y) * width + x) * 3]);
            }
        }
    });
    return image;
}

}  // namespace sl::bt
