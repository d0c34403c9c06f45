#include "beamtree/regions.h"

#include <tbb/parallel_for.h>

#include <fmt/format.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>

#include "beamtree/conforming.h"
#include "core/error.h"

namespace sl::bt {

size_t Regions::face_count(Region region) const {
    size_t count = 0;
    for (const RegionPiece& piece : pieces[size_t(region)]) {
        count += piece.polyhedron.faces.size();
    }
    return count;
}

bool Regions::drawn(Region region, const RegionPiece& piece) const {
    // Lit slivers — pieces thinner than 1e-5 of the influence volume's size (twice the volume
    // over the area) — stay out of the mesh: a ray crossing one integrates next to nothing, but
    // their faces are nearly edge-on to some pixel rays, where a rasterizer's interpolated depth
    // is off by far more than the sliver is thick and one face of the analytic pass's pair gives
    // ±G alone. (The other regions only bound intervals and keep every piece.)
    if (region != Region::lit) {
        return true;
    }
    double surface = 0.0;
    for (const Polygon& face : piece.polyhedron.faces) {
        surface += area(face);
    }
    return 2.0 * bt::volume(piece.polyhedron) >= 1e-5 * std::cbrt(influence_volume) * surface;
}

void RegionMesh::add_fanned(const Polygon& face, uint32_t beam) {
    if (face.size() < 3) {
        return;  // welded flat
    }
    const auto base = uint32_t(positions.size());
    for (const dvec3& v : face.vertices) {
        positions.emplace_back(v);
    }
    if (fan_triangles(face, [&](uint32_t a, uint32_t b, uint32_t c) {
            triangles.emplace_back(base + a, base + b, base + c);
            beams.push_back(beam);
        })) {
        positions.emplace_back(centroid(face));
    }
}

RegionMesh Regions::mesh(Region region) const {
    std::vector<Polygon> faces;
    std::vector<uint32_t> beams;
    for (const RegionPiece& piece : pieces[size_t(region)]) {
        if (drawn(region, piece)) {
            faces.insert(faces.end(), piece.polyhedron.faces.begin(), piece.polyhedron.faces.end());
            beams.resize(faces.size(), piece.beam);
        }
    }
    // Conforming across pieces (a face of one cell meets several of its neighbour's where the
    // tree split only that side), so that each pixel crosses every shared face exactly once.
    std::vector<Polygon*> pointers;
    for (Polygon& face : faces) {
        pointers.push_back(&face);
    }
    make_conforming(pointers, kConformingTolerance * std::cbrt(influence_volume));

    RegionMesh mesh;
    for (size_t f = 0; f < faces.size(); ++f) {
        mesh.add_fanned(faces[f], beams[f]);
    }
    return mesh;
}

Regions extract_regions(const BeamTree& tree) {
    Regions regions;
    // Vertices within this distance of a clipping plane count as on it.
    const double epsilon = Regions::kCutEpsilon * tree.epsilon();
    double far = 0.0;
    for (const Plane& plane : tree.influence_planes()) {
        far = std::max(far, std::abs(plane.distance(tree.apex())));
    }
    const dvec3 apex = tree.apex();
    // The influence volume around the origin-centred cube: translate by the apex for accuracy.
    std::vector<Plane> local_planes;
    for (const Plane& plane : tree.influence_planes()) {
        local_planes.push_back({plane.normal, plane.distance(apex)});
    }
    Polyhedron influence = polyhedron_from_planes(local_planes, 4.0 * far, epsilon);
    for (Polygon& face : influence.faces) {
        for (dvec3& v : face.vertices) {
            v += apex;
        }
    }
    regions.influence_volume = volume(influence);

    // Each leaf's cell cut by its occluder and stopper into up to three pieces (in parallel), then
    // gathered in the tree's order.
    std::vector<BeamTree::LeafCell> cells = tree.split_cells(std::move(influence), epsilon);
    std::vector<std::array<Polyhedron, 3>> cut(cells.size());
    tbb::parallel_for(size_t(0), cells.size(), [&](size_t i) {
        Polyhedron& cell = cells[i].cell;
        const Beam& beam = cells[i].beam;
        std::array<Polyhedron, 3>& parts = cut[i];
        if (!beam.has_occluder) {
            parts[size_t(Region::lit)] = std::move(cell);
            return;
        }
        parts[size_t(Region::lit)] = clip(cell, beam.occluder.flipped(), epsilon);
        Polyhedron behind = clip(cell, beam.occluder, epsilon);
        if (!beam.has_stopper) {
            parts[size_t(Region::uncertain)] = std::move(behind);
            return;
        }
        parts[size_t(Region::uncertain)] = clip(behind, beam.stopper.flipped(), epsilon);
        parts[size_t(Region::unlit)] = clip(behind, beam.stopper, epsilon);
    });
    // A piece is dropped only when it has no thickness at all (its faces lie on one plane from
    // both sides, to round-off: they cancel in every integral and bound nothing); a thin one
    // stays, or its neighbours' faces would not close up around the gap it leaves.
    const double flat = 1e-3 * epsilon;
    const uint32_t next_beam = uint32_t(cells.size());
    for (uint32_t b = 0; b < next_beam; ++b) {
        for (size_t r = 0; r < 3; ++r) {
            Polyhedron& polyhedron = cut[b][r];
            if (polyhedron.empty()) {
                continue;
            }
            const double v = volume(polyhedron);
            double surface = 0.0;
            for (const Polygon& face : polyhedron.faces) {
                surface += area(face);
            }
            if (!(v > 0.0) || 2.0 * v <= flat * surface) {
                continue;
            }
            regions.volume[r] += v;
            regions.pieces[r].push_back({b, std::move(polyhedron)});
        }
    }
    regions.beam_count = next_beam;
    return regions;
}

void write_regions_ply(const Regions& regions, const std::filesystem::path& path) {
    // Binary little-endian PLY: a large tree's regions are 10^6 faces, which as text took longer
    // to format than to compute (and 4x the space).
    size_t vertex_count = 0, face_count = 0;
    for (const auto& pieces : regions.pieces) {
        for (const RegionPiece& piece : pieces) {
            for (const Polygon& face : piece.polyhedron.faces) {
                vertex_count += face.size();
                ++face_count;
            }
        }
    }
    std::string data = fmt::format(
        "ply\nformat binary_little_endian 1.0\ncomment shaftlab beam-tree regions: region 0 lit, "
        "1 uncertain, 2 unlit\nelement vertex {}\nproperty double x\nproperty double y\n"
        "property double z\nelement face {}\nproperty list uchar int vertex_indices\n"
        "property uchar region\nproperty int beam\nend_header\n",
        vertex_count, face_count);
    auto append = [&](const auto& value) {
        static_assert(std::endian::native == std::endian::little);
        data.append(reinterpret_cast<const char*>(&value), sizeof(value));
    };
    for (const auto& pieces : regions.pieces) {
        for (const RegionPiece& piece : pieces) {
            for (const Polygon& face : piece.polyhedron.faces) {
                for (const dvec3& v : face.vertices) {
                    append(v.x), append(v.y), append(v.z);
                }
            }
        }
    }
    int32_t next = 0;
    for (size_t region = 0; region < 3; ++region) {
        for (const RegionPiece& piece : regions.pieces[region]) {
            for (const Polygon& face : piece.polyhedron.faces) {
                if (face.size() > 255) {
                    fail("{}: a region face of {} vertices does not fit a PLY uchar list",
                         path.string(), face.size());
                }
                append(uint8_t(face.size()));
                for (size_t i = 0; i < face.size(); ++i) {
                    append(next++);
                }
                append(uint8_t(region)), append(int32_t(piece.beam));
            }
        }
    }
    std::ofstream out(path, std::ios::binary);
    if (!out.write(data.data(), std::streamsize(data.size())) || !out.flush()) {
        fail("{}: cannot write PLY", path.string());
    }
}

}  // namespace sl::bt
