// Face clusters (beamtree/face_clusters.h): an object's faces cut into groups of spatial
// neighbours for the beam tree's hidden-cluster test. Checked against the faces themselves:
// every face in exactly one cluster, each cluster between half and all of its allowed size, each
// box holding its faces' corners and no bigger than they need, and the clusters compact (a
// random order of the faces gives the same boxes' total volume as a sorted one, far below the
// object's).

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <glm/common.hpp>

#include "beamtree/face_clusters.h"

namespace sl::test {
namespace {

using dvec3 = glm::dvec3;
using bt::Polygon;

// A grid of n × n unit squares on z = 0 (each a face), shuffled.
std::vector<Polygon> shuffled_grid(int n, unsigned seed) {
    std::vector<Polygon> faces;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const double x = i, y = j;
            faces.emplace_back(
                std::vector<dvec3>{{x, y, 0}, {x + 1, y, 0}, {x + 1, y + 1, 0}, {x, y + 1, 0}});
        }
    }
    std::mt19937 rng(seed);
    std::shuffle(faces.begin(), faces.end(), rng);
    return faces;
}

double area_of(const std::pair<dvec3, dvec3>& box) {
    const dvec3 e = box.second - box.first;
    return e.x * e.y;  // the grid is flat: the boxes' footprints
}

TEST(FaceClusters, EveryFaceIsInOneClusterOfBoundedSizeWhoseBoxHoldsItExactly) {
    for (const size_t per_cluster : {1u, 7u, 64u}) {
        const std::vector<Polygon> faces = shuffled_grid(30, unsigned(per_cluster));
        const bt::FaceClusters clusters = bt::cluster_faces(faces, per_cluster);
        ASSERT_EQ(clusters.cluster.size(), faces.size());
        std::vector<size_t> sizes(clusters.bounds.size(), 0);
        std::vector<std::pair<dvec3, dvec3>> tight(clusters.bounds.size(),
                                                   {dvec3(1e300), dvec3(-1e300)});
        for (size_t f = 0; f < faces.size(); ++f) {
            const uint32_t c = clusters.cluster[f];
            ASSERT_LT(c, clusters.bounds.size());
            ++sizes[c];
            for (const dvec3& v : faces[f].vertices) {
                tight[c].first = glm::min(tight[c].first, v);
                tight[c].second = glm::max(tight[c].second, v);
            }
        }
        double total = 0.0;
        for (size_t c = 0; c < sizes.size(); ++c) {
            EXPECT_LE(sizes[c], per_cluster);
            EXPECT_GE(2 * sizes[c], per_cluster) << "cluster " << c << " of " << sizes.size();
            EXPECT_EQ(clusters.bounds[c].first, tight[c].first) << "cluster " << c;
            EXPECT_EQ(clusters.bounds[c].second, tight[c].second) << "cluster " << c;
            total += area_of(clusters.bounds[c]);
        }
        // The faces listed by cluster: every face once, under its own cluster, in order.
        ASSERT_EQ(clusters.first.size(), clusters.bounds.size() + 1);
        ASSERT_EQ(clusters.first.back(), faces.size());
        ASSERT_EQ(clusters.faces.size(), faces.size());
        std::vector<int> listed(faces.size(), 0);
        for (size_t c = 0; c < clusters.bounds.size(); ++c) {
            EXPECT_EQ(clusters.first[c + 1] - clusters.first[c], sizes[c]) << "cluster " << c;
            for (uint32_t i = clusters.first[c]; i < clusters.first[c + 1]; ++i) {
                const uint32_t f = clusters.faces[i];
                ASSERT_LT(f, faces.size());
                ++listed[f];
                EXPECT_EQ(clusters.cluster[f], c) << "face " << f;
                if (i > clusters.first[c]) {
                    EXPECT_LT(clusters.faces[i - 1], f) << "cluster " << c;
                }
            }
        }
        EXPECT_EQ(std::count(listed.begin(), listed.end(), 1), std::ptrdiff_t(faces.size()));
        // Median splits of a grid of unit squares give boxes of about their faces' own area
        // (each box's footprint at most twice its faces' across a cut row); a cluster of faces
        // taken in the shuffled order would cover most of the grid each.
        EXPECT_LE(total, 2.0 * double(faces.size())) << per_cluster << " faces a cluster";
    }
}

TEST(FaceClusters, FacesOnOnePointStillEndInClusters) {
    std::vector<Polygon> faces(100, Polygon(std::vector<dvec3>(3, dvec3(1.0, 2.0, 3.0))));
    faces.emplace_back();  // no corners
    const bt::FaceClusters clusters = bt::cluster_faces(faces, 16);
    EXPECT_EQ(clusters.cluster.size(), faces.size());
    EXPECT_GE(clusters.bounds.size(), 101u / 16u);
    for (const uint32_t c : clusters.cluster) {
        EXPECT_LT(c, clusters.bounds.size());
    }
    EXPECT_EQ(clusters.faces.size(), faces.size());
    EXPECT_EQ(clusters.first.size(), clusters.bounds.size() + 1);
}

}  // namespace
}  // namespace sl::test
