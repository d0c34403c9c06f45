#include "beamtree/face_clusters.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include <glm/common.hpp>

#include "core/check.h"

namespace sl::bt {

namespace {

using Box = std::pair<dvec3, dvec3>;

Box empty_box() {
    return {dvec3(std::numeric_limits<double>::max()),
            dvec3(std::numeric_limits<double>::lowest())};
}

void grow(Box& box, const dvec3& p) {
    box.first = glm::min(box.first, p);
    box.second = glm::max(box.second, p);
}

}  // namespace

FaceClusters cluster_faces(const std::vector<Polygon>& faces, size_t per_cluster) {
    SL_CHECK(per_cluster >= 1);
    SL_CHECK(faces.size() < size_t(std::numeric_limits<uint32_t>::max()));
    std::vector<dvec3> centroids(faces.size(), dvec3(0.0));
    for (size_t f = 0; f < faces.size(); ++f) {
        for (const dvec3& v : faces[f].vertices) {
            centroids[f] += v / double(faces[f].size());
        }
    }
    std::vector<uint32_t> order(faces.size());
    std::iota(order.begin(), order.end(), 0u);
    FaceClusters clusters;
    clusters.cluster.assign(faces.size(), 0u);
    // Median splits of order[lo, hi) along the longest axis of its centroids' bounds; a range of
    // at most per_cluster faces is a cluster. Depth-first on an explicit stack: a degenerate mesh
    // (every centroid on one point) still halves each range, so it ends after log2 steps.
    std::vector<std::pair<size_t, size_t>> ranges;
    if (!faces.empty()) {
        ranges.push_back({0, faces.size()});
    }
    while (!ranges.empty()) {
        const auto [lo, hi] = ranges.back();
        ranges.pop_back();
        if (hi - lo <= per_cluster) {
            const auto index = uint32_t(clusters.bounds.size());
            // Depth-first, lower half first: the clusters' ranges follow each other in `order`.
            SL_CHECK(lo == (index == 0 ? 0 : clusters.first.back()));
            clusters.first.push_back(uint32_t(hi));
            std::sort(order.begin() + std::ptrdiff_t(lo), order.begin() + std::ptrdiff_t(hi));
            Box box = empty_box();
            for (size_t k = lo; k < hi; ++k) {
                clusters.cluster[order[k]] = index;
                for (const dvec3& v : faces[order[k]].vertices) {
                    grow(box, v);
                }
            }
            if (box.first.x > box.second.x) {
                box = {dvec3(0.0), dvec3(0.0)};  // faces without corners
            }
            clusters.bounds.push_back(box);
            continue;
        }
        Box spread = empty_box();
        for (size_t k = lo; k < hi; ++k) {
            grow(spread, centroids[order[k]]);
        }
        const dvec3 extent = spread.second - spread.first;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const size_t middle = lo + (hi - lo) / 2;
        std::nth_element(order.begin() + std::ptrdiff_t(lo), order.begin() + std::ptrdiff_t(middle),
                         order.begin() + std::ptrdiff_t(hi), [&](uint32_t a, uint32_t b) {
                             return centroids[a][axis] < centroids[b][axis];
                         });
        ranges.push_back({middle, hi});
        ranges.push_back({lo, middle});
    }
    clusters.first.insert(clusters.first.begin(), 0u);
    clusters.faces = std::move(order);
    return clusters;
}

}  // namespace sl::bt
