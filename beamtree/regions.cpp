#include "beamtree/regions.h"

#include <cmath>

#include <fmt/format.h>
#include <fmt/os.h>

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
        const std::vector<dvec3>& vertices = faces[f].vertices;
        if (vertices.size() < 3) {
            continue;  // welded flat
        }
        const auto base = uint32_t(mesh.positions.size());
        for (const dvec3& v : vertices) {
            mesh.positions.emplace_back(v);
        }
        if (fan_triangles(faces[f], [&](uint32_t a, uint32_t b, uint32_t c) {
                mesh.triangles.emplace_back(base + a, base + b, base + c);
                mesh.beams.push_back(beams[f]);
            })) {
            mesh.positions.emplace_back(centroid(faces[f]));
        }
    }
    return mesh;
}

Regions extract_regions(const BeamTree& tree) {
    Regions regions;
    // Vertices within this distance of a clipping plane count as on it; well below the tree's ε
    // so that the cells keep the tree's geometry.
    const double epsilon = 1e-3 * tree.epsilon();
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

    // Pieces thinner than round-off (slivers of cells that only touch a plane) are dropped:
    // they carry no volume, only faces.
    const double negligible = 1e-12 * regions.influence_volume;
    auto keep = [&](Region region, uint32_t beam, Polyhedron polyhedron) {
        const double v = volume(polyhedron);
        if (polyhedron.empty() || v <= negligible) {
            return;
        }
        regions.volume[size_t(region)] += v;
        regions.pieces[size_t(region)].push_back({beam, std::move(polyhedron)});
    };
    uint32_t next_beam = 0;
    tree.split_cells(std::move(influence), epsilon, [&](Polyhedron&& cell, const Beam& beam) {
        const uint32_t b = next_beam++;
        if (!beam.has_occluder) {
            keep(Region::lit, b, std::move(cell));
            return;
        }
        keep(Region::lit, b, clip(cell, beam.occluder.flipped(), epsilon));
        Polyhedron behind = clip(cell, beam.occluder, epsilon);
        if (!beam.has_stopper) {
            keep(Region::uncertain, b, std::move(behind));
            return;
        }
        keep(Region::uncertain, b, clip(behind, beam.stopper.flipped(), epsilon));
        keep(Region::unlit, b, clip(behind, beam.stopper, epsilon));
    });
    regions.beam_count = next_beam;
    return regions;
}

void write_regions_ply(const Regions& regions, const std::filesystem::path& path) {
    size_t vertex_count = 0, face_count = 0;
    for (const auto& pieces : regions.pieces) {
        for (const RegionPiece& piece : pieces) {
            for (const Polygon& face : piece.polyhedron.faces) {
                vertex_count += face.size();
                ++face_count;
            }
        }
    }
    try {
        auto out = fmt::output_file(path.string());
        out.print(
            "ply\nformat ascii 1.0\ncomment shaftlab beam-tree regions: region 0 lit, 1 "
            "uncertain, 2 unlit\nelement vertex {}\nproperty double x\nproperty double y\n"
            "property double z\nelement face {}\nproperty list uchar int vertex_indices\n"
            "property uchar region\nproperty int beam\nend_header\n",
            vertex_count, face_count);
        for (const auto& pieces : regions.pieces) {
            for (const RegionPiece& piece : pieces) {
                for (const Polygon& face : piece.polyhedron.faces) {
                    for (const dvec3& v : face.vertices) {
                        out.print("{} {} {}\n", v.x, v.y, v.z);
                    }
                }
            }
        }
        size_t next = 0;
        for (size_t region = 0; region < 3; ++region) {
            for (const RegionPiece& piece : regions.pieces[region]) {
                for (const Polygon& face : piece.polyhedron.faces) {
                    out.print("{}", face.size());
                    for (size_t i = 0; i < face.size(); ++i) {
                        out.print(" {}", next++);
                    }
                    out.print(" {} {}\n", region, piece.beam);
                }
            }
        }
    } catch (const std::exception& e) {
        fail("{}: cannot write PLY: {}", path.string(), e.what());
    }
}

}  // namespace sl::bt
