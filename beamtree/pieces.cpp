#include "beamtree/pieces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <set>
#include <tuple>

#include <glm/geometric.hpp>

#include "core/check.h"

namespace sl::bt {

namespace {

// The mesh's voxels: surface (touches a triangle), outside (reached from the padded border
// without crossing a surface voxel: empty space) or enclosed.
class Voxels {
public:
    enum State : uint8_t { enclosed = 0, surface = 1, outside = 2 };

    Voxels(const Mesh& mesh, int resolution) {
        const Bounds b = mesh.bounds();
        const dvec3 lo(b.min), hi(b.max);
        const double longest = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-30});
        cell_ = longest / resolution;
        // Two voxels of padding on every side: a face on the bounds touches the first (touching
        // counts), so the outermost layer is free for the flood fill all round.
        origin_ = lo - dvec3(2.0 * cell_);
        for (int a = 0; a < 3; ++a) {
            dims_[a] = int(std::ceil((hi[a] - lo[a]) / cell_)) + 5;
        }
        state_.assign(size_t(dims_[0]) * dims_[1] * dims_[2], enclosed);
        const dvec3 half(0.5 * cell_ * (1.0 + 1e-9));
        for (const glm::uvec3& t : mesh.triangles) {
            const dvec3 a(mesh.positions[t.x]), c1(mesh.positions[t.y]), c2(mesh.positions[t.z]);
            const glm::ivec3 from = voxel_of(glm::min(a, glm::min(c1, c2))) - 1;
            const glm::ivec3 to = voxel_of(glm::max(a, glm::max(c1, c2))) + 1;
            for (int z = std::max(from.z, 0); z <= std::min(to.z, dims_[2] - 1); ++z) {
                for (int y = std::max(from.y, 0); y <= std::min(to.y, dims_[1] - 1); ++y) {
                    for (int x = std::max(from.x, 0); x <= std::min(to.x, dims_[0] - 1); ++x) {
                        uint8_t& s = state_[index(x, y, z)];
                        if (s != surface &&
                            triangle_overlaps_box(a, c1, c2, center(x, y, z), half)) {
                            s = surface;
                        }
                    }
                }
            }
        }
        // Flood the outside from the corner (padding: never a surface voxel).
        std::vector<glm::ivec3> stack(1, glm::ivec3(0));
        state_[0] = outside;
        while (!stack.empty()) {
            const glm::ivec3 v = stack.back();
            stack.pop_back();
            for (int a = 0; a < 3; ++a) {
                for (const int step : {-1, 1}) {
                    glm::ivec3 n = v;
                    n[a] += step;
                    if (n[a] < 0 || n[a] >= dims_[a]) {
                        continue;
                    }
                    uint8_t& s = state_[index(n.x, n.y, n.z)];
                    if (s == enclosed) {
                        s = outside;
                        stack.push_back(n);
                    }
                }
            }
        }
    }

    double cell() const { return cell_; }
    // The voxel at p is empty space (outside the grid counts as empty).
    bool empty_at(const dvec3& p) const {
        const glm::ivec3 v = voxel_of(p);
        if (glm::any(glm::lessThan(v, glm::ivec3(0))) ||
            glm::any(glm::greaterThanEqual(v, dims_))) {
            return true;
        }
        return state_[index(v.x, v.y, v.z)] == outside;
    }

    // Voxels whose centres lie inside `hull` grown by half a voxel: {all, empty}.
    std::pair<int, int> count_inside(const ConvexVolume& hull) const {
        if (hull.empty()) {
            return {0, 0};
        }
        dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
        for (const Polygon& face : hull.faces) {
            for (const dvec3& v : face.vertices) {
                lo = glm::min(lo, v);
                hi = glm::max(hi, v);
            }
        }
        const glm::ivec3 from = glm::max(voxel_of(lo - dvec3(cell_)), glm::ivec3(0));
        const glm::ivec3 to = glm::min(voxel_of(hi + dvec3(cell_)), dims_ - 1);
        const double margin = -0.5 * cell_;
        int all = 0, empty = 0;
        for (int z = from.z; z <= to.z; ++z) {
            for (int y = from.y; y <= to.y; ++y) {
                for (int x = from.x; x <= to.x; ++x) {
                    if (hull.contains(center(x, y, z), margin)) {
                        ++all;
                        empty += state_[index(x, y, z)] == outside;
                    }
                }
            }
        }
        return {all, empty};
    }

private:
    size_t index(int x, int y, int z) const {
        return (size_t(z) * size_t(dims_[1]) + size_t(y)) * size_t(dims_[0]) + size_t(x);
    }
    dvec3 center(int x, int y, int z) const { return origin_ + cell_ * (dvec3(x, y, z) + 0.5); }
    glm::ivec3 voxel_of(const dvec3& p) const {
        return glm::ivec3(glm::floor((p - origin_) / cell_));
    }

    dvec3 origin_{0.0};
    double cell_ = 1.0;
    glm::ivec3 dims_{1};
    std::vector<uint8_t> state_;
};

// The polygon's part with lo <= p[axis] <= hi (Sutherland-Hodgman against two planes).
std::vector<dvec3> clip_slab(const std::vector<dvec3>& polygon, int axis, double lo, double hi) {
    auto clip = [&](const std::vector<dvec3>& in, double bound, double sign) {
        std::vector<dvec3> out;
        for (size_t i = 0; i < in.size(); ++i) {
            const dvec3& a = in[i];
            const dvec3& b = in[(i + 1) % in.size()];
            const double da = sign * (a[axis] - bound), db = sign * (b[axis] - bound);
            if (da >= 0.0) {
                out.push_back(a);
            }
            if ((da >= 0.0) != (db >= 0.0)) {
                dvec3 p = a + (b - a) * (da / (da - db));
                p[axis] = bound;  // exactly on the cut, so that neighbours share the points
                out.push_back(p);
            }
        }
        return out;
    };
    std::vector<dvec3> result = polygon;
    if (std::isfinite(lo)) {
        result = clip(result, lo, 1.0);
    }
    if (result.size() >= 3 && std::isfinite(hi)) {
        result = clip(result, hi, -1.0);
    }
    return result;
}

// Cut coordinates along one axis. Where the mesh has faces across the axis (a window's
// reveals, a sill, a floor), the planes of the largest of them, so that no cut an opening needs
// is thinned away; otherwise (a curved mesh) the distinct vertex coordinates, thinned evenly.
// Only coordinates strictly inside the bounds count, and at most `limit`.
// A shell (a room, an open box, a thin panel on the bounds) has its largest faces on the bounds,
// where no cut separates them: a face on the bounds with empty space behind it (probed 1.5
// voxels inward at its largest triangle) adds a cut one voxel inside (with `shells`), so that
// each such face becomes a slab of its own and the room's empty middle is left out.
// The faces of a mesh across one axis: the area on each plane strictly inside the bounds, and
// per side of the bounds the largest face on it (area, centre).
struct FacesAcross {
    std::map<double, double> area_at;
    std::array<std::pair<double, dvec3>, 2> on_bounds{};
};

FacesAcross faces_across(const Mesh& mesh, int axis, double lo, double hi) {
    FacesAcross out;
    for (const glm::uvec3& t : mesh.triangles) {
        const dvec3 p0(mesh.positions[t.x]), p1(mesh.positions[t.y]), p2(mesh.positions[t.z]);
        if (p0[axis] != p1[axis] || p1[axis] != p2[axis]) {
            continue;
        }
        const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
        if (p0[axis] > lo && p0[axis] < hi) {
            out.area_at[p0[axis]] += area;
        } else if (auto& side = out.on_bounds[p0[axis] >= hi ? 1 : 0]; area > side.first) {
            side = {area, (p0 + p1 + p2) / 3.0};
        }
    }
    return out;
}

// One cut a voxel inside each side of the bounds whose largest face has empty space behind it.
std::vector<double> shell_cuts(const FacesAcross& faces, int axis, const Bounds& b, double lo,
                               double hi, const Voxels& voxels) {
    std::vector<double> cuts;
    for (int side = 0; side < 2; ++side) {
        if (faces.on_bounds[size_t(side)].first <= 0.0 || hi - lo <= 3.0 * voxels.cell()) {
            continue;
        }
        dvec3 probe = faces.on_bounds[size_t(side)].second;
        probe[axis] += (side ? -1.5 : 1.5) * voxels.cell();
        if (voxels.empty_at(probe)) {
            cuts.push_back(side ? double(b.max[axis]) - voxels.cell()
                                : double(b.min[axis]) + voxels.cell());
        }
    }
    return cuts;
}

// The planes of the largest faces, none within `tolerance` of another, at most `slots`.
std::vector<double> cuts_at_faces(const std::map<double, double>& area_at, int slots,
                                  double tolerance) {
    std::vector<std::pair<double, double>> planes;  // (area, coordinate)
    for (const auto& [coordinate, area] : area_at) {
        planes.emplace_back(area, coordinate);
    }
    std::sort(planes.begin(), planes.end(), [](const auto& x, const auto& y) {
        return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    std::vector<double> cuts;
    for (const auto& plane : planes) {
        const double coordinate = plane.second;
        const bool near = std::any_of(cuts.begin(), cuts.end(), [&](double c) {
            return std::abs(c - coordinate) <= tolerance;
        });
        if (!near && int(cuts.size()) < slots) {
            cuts.push_back(coordinate);
        }
    }
    return cuts;
}

// The distinct vertex coordinates in (lo, hi) (closer than `tolerance` are one), thinned evenly
// to at most `slots`.
std::vector<double> cuts_at_vertices(const Mesh& mesh, int axis, double lo, double hi, int slots,
                                     double tolerance) {
    std::vector<double> values;
    for (const glm::vec3& p : mesh.positions) {
        if (double(p[axis]) > lo && double(p[axis]) < hi) {
            values.push_back(double(p[axis]));
        }
    }
    std::sort(values.begin(), values.end());
    std::vector<double> distinct;
    for (const double v : values) {
        if (distinct.empty() || v - distinct.back() > tolerance) {
            distinct.push_back(v);
        }
    }
    if (int(distinct.size()) <= slots) {
        return distinct;
    }
    std::vector<double> cuts;
    for (int i = 0; i < slots; ++i) {
        cuts.push_back(distinct[size_t((i + 0.5) * double(distinct.size()) / slots)]);
    }
    return cuts;
}

// Cut coordinates along one axis. Where the mesh has faces across the axis (a window's
// reveals, a sill, a floor), the planes of the largest of them, so that no cut an opening needs
// is thinned away; otherwise (a curved mesh) the distinct vertex coordinates, thinned evenly.
// Only coordinates strictly inside the bounds count, and at most `limit`.
// A shell (a room, an open box, a thin panel on the bounds) has its largest faces on the bounds,
// where no cut separates them: a face on the bounds with empty space behind it (probed 1.5
// voxels inward at its largest triangle) adds a cut one voxel inside (with `shells`), so that
// each such face becomes a slab of its own and the room's empty middle is left out.
std::vector<double> cuts_along(const Mesh& mesh, int axis, int limit, double tolerance,
                               const Voxels& voxels, bool shells) {
    const Bounds b = mesh.bounds();
    const double lo = double(b.min[axis]) + tolerance, hi = double(b.max[axis]) - tolerance;
    const FacesAcross faces = faces_across(mesh, axis, lo, hi);
    const std::vector<double> shell =
        shells ? shell_cuts(faces, axis, b, lo, hi, voxels) : std::vector<double>();
    const int slots = limit - int(shell.size());
    std::vector<double> cuts = !faces.area_at.empty()
                                   ? cuts_at_faces(faces.area_at, slots, tolerance)
                                   : cuts_at_vertices(mesh, axis, lo, hi, slots, tolerance);
    for (const double c : shell) {
        const bool near = std::any_of(cuts.begin(), cuts.end(), [&](double other) {
            return std::abs(other - c) <= 0.5 * voxels.cell();
        });
        if (!near && int(cuts.size()) < limit) {
            cuts.push_back(c);
        }
    }
    std::sort(cuts.begin(), cuts.end());
    return cuts;
}

struct Piece {
    Mesh mesh;
    ConvexVolume hull;
    int all = 0;    // voxels inside the hull
    int empty = 0;  // empty voxels inside the hull
    int version = 0;
    bool alive = true;
    std::set<int> neighbours;
};

// A convex volume as a mesh (its faces fanned): the hull of two pieces is the hull of their two
// hulls, so a piece is carried as its hull, a few dozen points however many triangles it holds.
Mesh hull_mesh(const ConvexVolume& hull) {
    Mesh mesh;
    for (const Polygon& face : hull.faces) {
        const auto base = uint32_t(mesh.positions.size());
        for (const dvec3& v : face.vertices) {
            mesh.positions.emplace_back(v);
        }
        for (uint32_t k = 1; k + 1 < face.vertices.size(); ++k) {
            mesh.triangles.emplace_back(base, base + k, base + k + 1);
        }
        if (hull.flat) {
            break;  // one side of a flat hull is all of it
        }
    }
    return mesh;
}

void append(Mesh& to, const Mesh& from) {
    const auto base = uint32_t(to.positions.size());
    to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
    for (const glm::uvec3& t : from.triangles) {
        to.triangles.push_back(t + base);
    }
}

using CellIndex = std::array<size_t, 3>;

// The cells between the cut planes of each axis, by index (slot i of axis a lies between cut i-1
// and cut i), each with the parts of the mesh's triangles inside it.
class CellGrid {
public:
    CellGrid(const std::array<std::vector<double>, 3>& cuts, double extent)
        : cuts_(cuts), min_area_(1e-14 * extent * extent) {}

    // Clips every triangle into the cells; a polygon on a cut goes to the cell on its solid side.
    std::map<CellIndex, Mesh> cut(const Mesh& mesh, const Voxels& voxels) const {
        std::map<CellIndex, Mesh> cells;
        for (const glm::uvec3& t : mesh.triangles) {
            for (auto& [index, polygon] :
                 clip({dvec3(mesh.positions[t.x]), dvec3(mesh.positions[t.y]),
                       dvec3(mesh.positions[t.z])})) {
                to_solid_side(polygon, voxels, index);
                add(cells[index], polygon);
            }
        }
        return cells;
    }

private:
    double bound(int a, size_t i, bool upper) const {
        const std::vector<double>& c = cuts_[size_t(a)];
        if (upper) {
            return i < c.size() ? c[i] : std::numeric_limits<double>::infinity();
        }
        return i > 0 ? c[i - 1] : -std::numeric_limits<double>::infinity();
    }
    size_t slot(int a, double v) const {
        const std::vector<double>& c = cuts_[size_t(a)];
        return size_t(std::upper_bound(c.begin(), c.end(), v) - c.begin());
    }

    // The triangle's parts in each cell: x slabs, then y, then z.
    std::vector<std::pair<CellIndex, std::vector<dvec3>>> clip(
        const std::vector<dvec3>& triangle) const {
        std::vector<std::pair<CellIndex, std::vector<dvec3>>> level{{{0, 0, 0}, triangle}};
        for (int a = 0; a < 3; ++a) {
            std::vector<std::pair<CellIndex, std::vector<dvec3>>> next;
            for (auto& [index, polygon] : level) {
                double lo = std::numeric_limits<double>::max(),
                       hi = std::numeric_limits<double>::lowest();
                for (const dvec3& p : polygon) {
                    lo = std::min(lo, p[a]);
                    hi = std::max(hi, p[a]);
                }
                const size_t first = slot(a, lo), last = slot(a, hi);
                for (size_t i = first; i <= last; ++i) {
                    std::vector<dvec3> part =
                        first == last
                            ? polygon
                            : clip_slab(polygon, a, bound(a, i, false), bound(a, i, true));
                    if (part.size() >= 3) {
                        CellIndex cell = index;
                        cell[size_t(a)] = i;
                        next.emplace_back(cell, std::move(part));
                    }
                }
            }
            level = std::move(next);
        }
        return level;
    }

    // A polygon on its cell's lower cut plane (polygons on a cut go to the upper cell) belongs to
    // the cell on its solid side: a window's reveal or sill would otherwise span the opening's
    // cell. Probed at its centroid, past the voxels it touches.
    void to_solid_side(const std::vector<dvec3>& polygon, const Voxels& voxels,
                       CellIndex& index) const {
        dvec3 centre(0.0);
        for (const dvec3& p : polygon) {
            centre += p / double(polygon.size());
        }
        for (int a = 0; a < 3; ++a) {
            const size_t i = index[size_t(a)];
            if (i == 0 || std::any_of(polygon.begin(), polygon.end(), [&](const dvec3& p) {
                    return p[a] != cuts_[size_t(a)][i - 1];
                })) {
                continue;
            }
            dvec3 step(0.0);
            step[a] = 1.5 * voxels.cell();
            if (voxels.empty_at(centre + step) && !voxels.empty_at(centre - step)) {
                --index[size_t(a)];
            }
        }
    }

    // The polygon fanned into the cell's mesh, without triangles of no area.
    void add(Mesh& cell, const std::vector<dvec3>& polygon) const {
        const auto base = uint32_t(cell.positions.size());
        for (const dvec3& p : polygon) {
            cell.positions.emplace_back(p);
        }
        for (uint32_t k = 1; k + 1 < polygon.size(); ++k) {
            const dvec3 n = glm::cross(polygon[k] - polygon[0], polygon[k + 1] - polygon[0]);
            if (0.5 * glm::length(n) > min_area_) {
                cell.triangles.emplace_back(base, base + k, base + k + 1);
            }
        }
    }

    const std::array<std::vector<double>, 3>& cuts_;
    double min_area_;
};

// One piece per cell that holds a triangle (slivers of no area hold nothing a ray can meet),
// each the neighbour of the pieces of the cells beside it.
std::vector<Piece> cell_pieces(const std::map<CellIndex, Mesh>& cells, const Voxels& voxels) {
    std::vector<Piece> pieces;
    std::map<CellIndex, int> piece_of;
    for (const auto& [index, cell] : cells) {
        if (cell.triangles.empty()) {
            continue;
        }
        Piece piece;
        piece.hull = convex_hull(cell, 0);
        std::tie(piece.all, piece.empty) = voxels.count_inside(piece.hull);
        piece.mesh = hull_mesh(piece.hull);
        piece_of[index] = int(pieces.size());
        pieces.push_back(std::move(piece));
    }
    for (const auto& [index, p] : piece_of) {
        for (int a = 0; a < 3; ++a) {
            CellIndex next = index;
            ++next[size_t(a)];
            if (const auto it = piece_of.find(next); it != piece_of.end()) {
                pieces[size_t(p)].neighbours.insert(it->second);
                pieces[size_t(it->second)].neighbours.insert(p);
            }
        }
    }
    return pieces;
}

// Merges neighbouring pieces greedily, least added empty space first (ties: fewer triangles),
// while the merged hull adds no more empty voxels than the slack, and beyond the budget of pieces
// the least bad merges anyway. Stale queue entries are skipped by their versions.
class PieceMerger {
public:
    PieceMerger(std::vector<Piece> pieces, const Voxels& voxels, const PieceOptions& options)
        : pieces_(std::move(pieces)),
          voxels_(voxels),
          options_(options),
          alive_(int(pieces_.size())) {}

    void merge_neighbours() {
        for (int p = 0; p < int(pieces_.size()); ++p) {
            for (const int n : pieces_[size_t(p)].neighbours) {
                if (n > p) {
                    consider(p, n);
                }
            }
        }
        while (!queue_.empty()) {
            const Candidate top = queue_.top();
            queue_.pop();
            const Piece& pa = pieces_[size_t(top.a)];
            const Piece& pb = pieces_[size_t(top.b)];
            if (!pa.alive || !pb.alive || pa.version != top.version_a ||
                pb.version != top.version_b) {
                continue;
            }
            Piece merged = merged_of(top.a, top.b);
            if (double(added(merged, top.a, top.b)) > allowed(merged.all) &&
                alive_ <= options_.max_pieces) {
                continue;  // too loose, and no need to merge it
            }
            merge(top.a, top.b, std::move(merged));
        }
    }

    // Pieces in no contact with each other (separate parts) can still exceed the budget: the
    // least-added-space pairs among all are merged.
    void merge_to_budget() {
        while (alive_ > options_.max_pieces) {
            int best_a = -1, best_b = -1, best_added = std::numeric_limits<int>::max();
            for (int a = 0; a < int(pieces_.size()); ++a) {
                for (int c = a + 1; c < int(pieces_.size()) && pieces_[size_t(a)].alive; ++c) {
                    if (pieces_[size_t(c)].alive) {
                        const int d = added(merged_of(a, c), a, c);
                        if (d < best_added) {
                            std::tie(best_a, best_b, best_added) = std::tie(a, c, d);
                        }
                    }
                }
            }
            SL_CHECK(best_a >= 0);
            merge(best_a, best_b, merged_of(best_a, best_b));
        }
    }

    std::vector<Piece>& pieces() { return pieces_; }

private:
    struct Candidate {
        int added;
        size_t triangles;
        int a, b, version_a, version_b;
        bool operator>(const Candidate& o) const {
            return std::tie(added, triangles, a, b) > std::tie(o.added, o.triangles, o.a, o.b);
        }
    };

    double allowed(int all) const {
        return std::max(double(options_.slack_voxels), options_.slack * double(all));
    }
    Piece merged_of(int a, int c) const {
        Piece merged;
        merged.mesh = pieces_[size_t(a)].mesh;
        append(merged.mesh, pieces_[size_t(c)].mesh);
        merged.hull = convex_hull(merged.mesh, 0);
        std::tie(merged.all, merged.empty) = voxels_.count_inside(merged.hull);
        merged.mesh = hull_mesh(merged.hull);
        return merged;
    }
    int added(const Piece& merged, int a, int c) const {
        return merged.empty - pieces_[size_t(a)].empty - pieces_[size_t(c)].empty;
    }
    void consider(int a, int c) {
        const Piece merged = merged_of(a, c);
        queue_.push({added(merged, a, c), merged.mesh.triangles.size(), std::min(a, c),
                     std::max(a, c), pieces_[size_t(std::min(a, c))].version,
                     pieces_[size_t(std::max(a, c))].version});
    }
    void merge(int a, int c, Piece merged) {
        merged.neighbours = pieces_[size_t(a)].neighbours;
        merged.neighbours.insert(pieces_[size_t(c)].neighbours.begin(),
                                 pieces_[size_t(c)].neighbours.end());
        merged.neighbours.erase(a);
        merged.neighbours.erase(c);
        merged.version = pieces_[size_t(a)].version + 1;
        pieces_[size_t(c)].alive = false;
        ++pieces_[size_t(c)].version;
        for (const int n : merged.neighbours) {
            pieces_[size_t(n)].neighbours.erase(c);
            pieces_[size_t(n)].neighbours.insert(a);
        }
        pieces_[size_t(a)] = std::move(merged);
        --alive_;
        for (const int n : pieces_[size_t(a)].neighbours) {
            consider(a, n);
        }
    }

    std::vector<Piece> pieces_;
    const Voxels& voxels_;
    const PieceOptions& options_;
    int alive_;
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue_;
};

// Cells between the cut planes, each with the triangles clipped to it, merged.
Pieces cut_and_merge(const Mesh& mesh, const Voxels& voxels, const PieceOptions& options,
                     const std::array<std::vector<double>, 3>& cuts, double extent) {
    PieceMerger merger(cell_pieces(CellGrid(cuts, extent).cut(mesh, voxels), voxels), voxels,
                       options);
    Pieces result;
    result.cells = int(merger.pieces().size());
    merger.merge_neighbours();
    merger.merge_to_budget();
    for (Piece& piece : merger.pieces()) {
        if (piece.alive) {
            result.empty_voxels_pieces += piece.empty;
            result.parts.push_back(std::move(piece.mesh));
        }
    }
    return result;
}

}  // namespace

Pieces convex_pieces(const Mesh& mesh, const PieceOptions& options) {
    Pieces result;
    const Voxels voxels(mesh, options.voxels);
    auto allowed = [&](int all) {
        return std::max(double(options.slack_voxels), options.slack * double(all));
    };
    const ConvexVolume whole = convex_hull(mesh, 0);
    const auto [whole_all, whole_empty] = voxels.count_inside(whole);
    result.empty_voxels_whole = whole_empty;
    if (double(whole_empty) <= allowed(whole_all)) {
        result.whole = true;
        result.cells = 1;
        result.empty_voxels_pieces = whole_empty;
        result.parts.push_back(mesh);
        return result;
    }

    const double extent = max_extent(mesh.bounds());
    std::array<std::vector<double>, 3> cuts, shell_cuts;
    for (int a = 0; a < 3; ++a) {
        cuts[size_t(a)] = cuts_along(mesh, a, options.max_cuts, 1e-6 * extent, voxels, false);
        shell_cuts[size_t(a)] = cuts_along(mesh, a, options.max_cuts, 1e-6 * extent, voxels, true);
    }
    Pieces pieces = cut_and_merge(mesh, voxels, options, cuts, extent);
    if (shell_cuts != cuts) {
        // The shell cuts help rooms and open boxes; where they do not, the extra cells only
        // cost: the decomposition with less empty space in its hulls is kept.
        Pieces shells = cut_and_merge(mesh, voxels, options, shell_cuts, extent);
        if (shells.empty_voxels_pieces < pieces.empty_voxels_pieces ||
            (shells.empty_voxels_pieces == pieces.empty_voxels_pieces &&
             shells.parts.size() < pieces.parts.size())) {
            pieces = std::move(shells);
        }
    }
    pieces.empty_voxels_whole = whole_empty;
    return pieces;
}

std::vector<int> empty_voxels_inside(const Mesh& mesh, const std::vector<ConvexVolume>& hulls,
                                     const PieceOptions& options) {
    const Voxels voxels(mesh, options.voxels);
    std::vector<int> result;
    for (const ConvexVolume& hull : hulls) {
        result.push_back(voxels.count_inside(hull).second);
    }
    return result;
}

}  // namespace sl::bt

namespace sl::bt {

namespace {

using EdgeKey = std::pair<uint32_t, uint32_t>;  // smaller vertex first
using EdgeSplits = std::map<EdgeKey, std::vector<std::pair<double, uint32_t>>>;

EdgeKey edge_key(uint32_t a, uint32_t b) {
    return {std::min(a, b), std::max(a, b)};
}

// Vertices within `tolerance` on one grid cell become one; triangles that lose a corner go.
Mesh weld_vertices(const Mesh& mesh, double tolerance) {
    Mesh out;
    std::map<std::tuple<long long, long long, long long>, uint32_t> cells;
    std::vector<uint32_t> map(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
        const dvec3 p(mesh.positions[i]);
        const auto key =
            std::make_tuple(std::llround(p.x / tolerance), std::llround(p.y / tolerance),
                            std::llround(p.z / tolerance));
        const auto [it, added] = cells.try_emplace(key, uint32_t(out.positions.size()));
        if (added) {
            out.positions.push_back(mesh.positions[i]);
        }
        map[i] = it->second;
    }
    for (const glm::uvec3& t : mesh.triangles) {
        const glm::uvec3 w(map[t.x], map[t.y], map[t.z]);
        if (w.x != w.y && w.y != w.z && w.z != w.x) {
            out.triangles.push_back(w);
        }
    }
    return out;
}

// T-junctions: the vertices of open edges (used by one triangle) that lie within `tolerance` on
// another open edge, per edge with their parameter along it (from the smaller vertex).
EdgeSplits t_junctions(const Mesh& mesh, double tolerance) {
    std::map<EdgeKey, int> uses;
    for (const glm::uvec3& t : mesh.triangles) {
        for (int e = 0; e < 3; ++e) {
            ++uses[edge_key(t[e], t[(e + 1) % 3])];
        }
    }
    std::set<uint32_t> open_vertices;
    std::vector<EdgeKey> open_edges;
    for (const auto& [edge, count] : uses) {
        if (count == 1) {
            open_edges.push_back(edge);
            open_vertices.insert(edge.first);
            open_vertices.insert(edge.second);
        }
    }
    EdgeSplits splits;
    constexpr size_t kMaxOpenEdges = 20000;  // beyond it the quadratic search is not worth it
    if (open_edges.size() > kMaxOpenEdges) {
        return splits;
    }
    for (const auto& [a, b] : open_edges) {
        const dvec3 pa(mesh.positions[a]), pb(mesh.positions[b]);
        const dvec3 d = pb - pa;
        const double length2 = glm::dot(d, d);
        for (const uint32_t v : open_vertices) {
            if (v == a || v == b) {
                continue;
            }
            const dvec3 pv(mesh.positions[v]);
            const double s = glm::dot(pv - pa, d) / length2;
            if (s > 1e-9 && s < 1.0 - 1e-9 && glm::length(pa + s * d - pv) <= tolerance) {
                splits[{a, b}].emplace_back(s, v);
            }
        }
    }
    return splits;
}

// Each triangle with a split edge becomes a fan from a new centre vertex around its corners and
// the split points in order: no triangle is degenerate, every split edge is kept.
void split_edges(Mesh& mesh, const EdgeSplits& splits) {
    std::vector<glm::uvec3> triangles;
    for (const glm::uvec3& t : mesh.triangles) {
        std::vector<uint32_t> ring;
        bool split = false;
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = t[e], b = t[(e + 1) % 3];
            ring.push_back(a);
            const auto it = splits.find(edge_key(a, b));
            if (it == splits.end()) {
                continue;
            }
            std::vector<std::pair<double, uint32_t>> points = it->second;
            std::sort(points.begin(), points.end());
            if (a > b) {  // stored from the smaller index: walk it the other way
                std::reverse(points.begin(), points.end());
            }
            for (const auto& point : points) {
                ring.push_back(point.second);
            }
            split = true;
        }
        if (!split) {
            triangles.push_back(t);
            continue;
        }
        const glm::vec3 centre =
            (mesh.positions[t.x] + mesh.positions[t.y] + mesh.positions[t.z]) / 3.0f;
        const auto c = uint32_t(mesh.positions.size());
        mesh.positions.push_back(centre);
        for (size_t k = 0; k < ring.size(); ++k) {
            triangles.emplace_back(c, ring[k], ring[(k + 1) % ring.size()]);
        }
    }
    mesh.triangles = std::move(triangles);
}

}  // namespace

Mesh welded(const Mesh& mesh, double tolerance) {
    Mesh out = weld_vertices(mesh, tolerance);
    const EdgeSplits splits = t_junctions(out, tolerance);
    if (!splits.empty()) {
        split_edges(out, splits);
    }
    return out;
}

}  // namespace sl::bt
