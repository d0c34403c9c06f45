#include "beamtree/bounding_volumes.h"

#include <tbb/parallel_for.h>

#include <set>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "beamtree/pieces.h"
#include "core/cache.h"
#include "core/error.h"
#include "core/hash.h"
#include "core/progress.h"

namespace sl::bt {

namespace {

// A mesh's triangles in double precision with their bounding boxes, for many box queries.
class TriangleSet {
public:
    explicit TriangleSet(const Mesh& mesh) {
        for (const glm::uvec3& t : mesh.triangles) {
            const dvec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
            corners_.push_back({a, b, c});
            lo_.push_back(glm::min(a, glm::min(b, c)));
            hi_.push_back(glm::max(a, glm::max(b, c)));
        }
    }
    // True when no triangle touches the closed box.
    bool misses(const Box& box) const {
        const dvec3 lo(box.min), hi(box.max);
        const dvec3 center = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
        for (size_t i = 0; i < corners_.size(); ++i) {
            if (hi_[i].x < lo.x || hi_[i].y < lo.y || hi_[i].z < lo.z || lo_[i].x > hi.x ||
                lo_[i].y > hi.y || lo_[i].z > hi.z) {
                continue;
            }
            const auto& [a, b, c] = corners_[i];
            if (triangle_overlaps_box(a, b, c, center, half)) {
                return false;
            }
        }
        return true;
    }

private:
    std::vector<std::array<dvec3, 3>> corners_;
    std::vector<dvec3> lo_, hi_;
};

}  // namespace

bool box_inside_mesh(const Mesh& mesh, const Box& box) {
    const glm::vec3 center = 0.5f * (box.min + box.max);
    return TriangleSet(mesh).misses(box) && point_inside_mesh(mesh, dvec3(center));
}

std::optional<Box> inscribed_box(const Mesh& mesh) {
    const Bounds bounds = mesh.bounds();
    const glm::vec3 half = 0.5f * bounds.extent();
    auto box_at = [](glm::vec3 c, glm::vec3 h) { return Box{c - h, c + h}; };

    // Seeds: the box centre and a coarse grid of cell centres that lie inside the mesh; from each,
    // the largest box of the mesh's proportions (binary search on its scale).
    std::vector<glm::vec3> seeds = {bounds.center()};
    constexpr int kGrid = 4;
    for (int i = 0; i < kGrid; ++i) {
        for (int j = 0; j < kGrid; ++j) {
            for (int k = 0; k < kGrid; ++k) {
                const glm::vec3 f((i + 0.5f) / kGrid, (j + 0.5f) / kGrid, (k + 0.5f) / kGrid);
                seeds.push_back(bounds.min + f * bounds.extent());
            }
        }
    }
    const TriangleSet triangles(mesh);
    auto no_triangle_touches = [&](const Mesh&, const Box& box) { return triangles.misses(box); };
    float best_scale = 0.0f;
    glm::vec3 best_center(0.0f);
    for (const glm::vec3& seed : seeds) {
        // A box that touches no triangle around an inside seed stays inside the mesh's bounds,
        // whose faces all touch the mesh: the scale reachable from this seed is below the
        // distance to the nearest bound. Seeds that cannot beat the best are skipped before the
        // winding number, the expensive test (the result is the same).
        float bound = 1.0f;
        for (int axis = 0; axis < 3; ++axis) {
            if (half[axis] > 0.0f) {
                bound = std::min(
                    bound, std::min(seed[axis] - bounds.min[axis], bounds.max[axis] - seed[axis]) /
                               half[axis]);
            }
        }
        if (bound <= best_scale || !point_inside_mesh(mesh, dvec3(seed))) {
            continue;
        }
        float lo = 0.0f, hi = 1.0f;
        if (!no_triangle_touches(mesh, box_at(seed, lo + 1e-6f * half))) {
            continue;
        }
        for (int iteration = 0; iteration < 16; ++iteration) {
            const float mid = 0.5f * (lo + hi);
            (no_triangle_touches(mesh, box_at(seed, mid * half)) ? lo : hi) = mid;
        }
        if (lo > best_scale) {
            best_scale = lo;
            best_center = seed;
        }
    }
    if (best_scale <= 0.0f) {
        return std::nullopt;
    }
    // Then push each face out as far as it goes.
    Box box = box_at(best_center, best_scale * half);
    for (int round = 0; round < 2; ++round) {
        for (int axis = 0; axis < 3; ++axis) {
            for (const bool upper : {false, true}) {
                float lo = 0.0f, hi = bounds.extent()[axis];
                for (int iteration = 0; iteration < 14; ++iteration) {
                    const float mid = 0.5f * (lo + hi);
                    Box grown = box;
                    (upper ? grown.max[axis] : grown.min[axis]) += upper ? mid : -mid;
                    (no_triangle_touches(mesh, grown) ? lo : hi) = mid;
                }
                (upper ? box.max[axis] : box.min[axis]) += upper ? lo : -lo;
            }
        }
    }
    return box;
}

namespace {

// The largest box of a piece's proportions about its hull's vertex centroid that stays inside
// the hull and touches no triangle of the mesh, with its centre inside the (closed) mesh.
std::optional<Box> box_in_piece(const ConvexVolume& hull, const TriangleSet& triangles,
                                const Mesh& closed_mesh) {
    dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    dvec3 sum(0.0);
    size_t count = 0;
    for (const Polygon& face : hull.faces) {
        for (const dvec3& v : face.vertices) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
            sum += v;
            ++count;
        }
    }
    if (count == 0 || hull.flat) {
        return std::nullopt;
    }
    const dvec3 center = sum / double(count);
    const dvec3 half = 0.5 * (hi - lo);
    auto box_at = [&](double scale) {
        return Box{glm::vec3(center - scale * half), glm::vec3(center + scale * half)};
    };
    auto fits = [&](double scale) {
        const Box box = box_at(scale);
        for (int corner = 0; corner < 8; ++corner) {
            const dvec3 p(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                          corner & 4 ? box.max.z : box.min.z);
            if (!hull.contains(p, 0.0)) {
                return false;
            }
        }
        return triangles.misses(box);
    };
    if (!fits(1e-4)) {
        return std::nullopt;
    }
    double a = 1e-4, b = 1.0;
    for (int iteration = 0; iteration < 14; ++iteration) {
        const double mid = 0.5 * (a + b);
        (fits(mid) ? a : b) = mid;
    }
    if (!point_inside_mesh(closed_mesh, center)) {
        return std::nullopt;
    }
    // Then each face pushed out as far as it goes (the piece need not be centred on its
    // vertices' centroid).
    Box box = box_at(a);
    auto box_fits = [&](const Box& candidate) {
        for (int corner = 0; corner < 8; ++corner) {
            const dvec3 p(corner & 1 ? candidate.max.x : candidate.min.x,
                          corner & 2 ? candidate.max.y : candidate.min.y,
                          corner & 4 ? candidate.max.z : candidate.min.z);
            if (!hull.contains(p, 0.0)) {
                return false;
            }
        }
        return triangles.misses(candidate);
    };
    for (int axis = 0; axis < 3; ++axis) {
        for (const bool upper : {false, true}) {
            float grow_lo = 0.0f, grow_hi = float(hi[axis] - lo[axis]);
            for (int iteration = 0; iteration < 14; ++iteration) {
                const float mid = 0.5f * (grow_lo + grow_hi);
                Box grown = box;
                (upper ? grown.max[axis] : grown.min[axis]) += upper ? mid : -mid;
                (box_fits(grown) ? grow_lo : grow_hi) = mid;
            }
            (upper ? box.max[axis] : box.min[axis]) += upper ? grow_lo : -grow_lo;
        }
    }
    return box;
}

}  // namespace

LocalVolumes VolumeLibrary::compute(const Mesh& mesh) const {
    LocalVolumes volumes;
    volumes.outer = convex_hull(mesh, options_.max_outer_planes);
    // Closed as drawn, or once welded with its T-junctions split (beamtree/pieces.h); the
    // inner volumes are verified against that closed mesh.
    const Mesh repaired = welded(mesh, 1e-6 * max_extent(mesh.bounds()));
    volumes.closed = mesh.is_closed() || repaired.is_closed();
    const Mesh& closed_mesh = mesh.is_closed() ? mesh : repaired;
    if (volumes.outer.flat) {
        const double hull_area = area(volumes.outer.faces[0]);
        volumes.self_inner = std::abs(mesh.area() - hull_area) <= 1e-6 * hull_area;
        return volumes;
    }
    if (options_.pieces && options_.max_outer_planes == 0) {
        const Pieces pieces = convex_pieces(mesh);
        volumes.cells = pieces.cells;
        volumes.empty_voxels_whole = pieces.empty_voxels_whole;
        volumes.empty_voxels_pieces = pieces.empty_voxels_pieces;
        if (!pieces.whole) {
            const TriangleSet triangles(closed_mesh);
            for (const Mesh& part : pieces.parts) {
                LocalPiece piece;
                // Grown: neighbouring pieces share their cut faces exactly, and coincident
                // opposite faces are what the boundary extraction cannot tell apart; grown, they
                // overlap by a sliver instead.
                piece.outer = inflated(convex_hull(part, 0), 1e-4 * max_extent(mesh.bounds()));
                if (options_.automatic_inner && volumes.closed) {
                    if (const std::optional<Box> box =
                            box_in_piece(piece.outer, triangles, closed_mesh)) {
                        piece.inner.push_back(box_volume(*box));
                    }
                }
                volumes.pieces.push_back(std::move(piece));
            }
        }
    }
    if (options_.automatic_inner && volumes.closed && volumes.pieces.empty()) {
        if (const std::optional<Box> box = inscribed_box(closed_mesh)) {
            volumes.automatic_inner.push_back(box_volume(*box));
        }
    }
    const bool any_inner = !volumes.automatic_inner.empty() ||
                           std::any_of(volumes.pieces.begin(), volumes.pieces.end(),
                                       [](const LocalPiece& p) { return !p.inner.empty(); });
    if (!options_.automatic_inner) {
        volumes.no_inner = "automatic inner volumes are off";
    } else if (!volumes.closed) {
        volumes.no_inner = "the mesh is not closed, even welded with its T-junctions split";
    } else if (!any_inner) {
        volumes.no_inner = "no box fits inside it (too thin, or no inside point found)";
    }
    return volumes;
}

namespace {

constexpr std::string_view kVolumesVersion = "shaftlab-volumes-12";

// LocalVolumes known to this process, by content key: libraries share them.
std::mutex& process_mutex() {
    static std::mutex mutex;
    return mutex;
}
std::map<uint64_t, std::shared_ptr<const LocalVolumes>>& process_volumes() {
    static std::map<uint64_t, std::shared_ptr<const LocalVolumes>> volumes;
    return volumes;
}

template <typename T>
uint64_t mix(uint64_t hash, const T* data, size_t count) {
    return fnv1a(std::string_view(reinterpret_cast<const char*>(data), count * sizeof(T)), hash);
}

std::filesystem::path volumes_file(uint64_t key) {
    return cache_directory() / "volumes" / fmt::format("{:016x}.bin", key);
}

// The cache file: the version, then each volume as its flag, faces (vertex lists) and planes,
// in doubles, so that a volume read back is bit-identical to the one computed.
class Writer {
public:
    explicit Writer(std::ostream& out) : out_(out) {}
    template <typename T>
    void value(const T& v) {
        out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    void volume(const ConvexVolume& v) {
        value(uint8_t(v.flat));
        value(uint64_t(v.faces.size()));
        for (size_t i = 0; i < v.faces.size(); ++i) {
            value(v.faces[i].on_split_plane);
            value(uint64_t(v.faces[i].vertices.size()));
            out_.write(reinterpret_cast<const char*>(v.faces[i].vertices.data()),
                       std::streamsize(v.faces[i].vertices.size() * sizeof(dvec3)));
            value(v.planes[i]);
        }
    }

private:
    std::ostream& out_;
};

class Reader {
public:
    explicit Reader(std::istream& in) : in_(in) {}
    template <typename T>
    T value() {
        T v{};
        in_.read(reinterpret_cast<char*>(&v), sizeof(T));
        if (!in_) {
            throw std::runtime_error("truncated");
        }
        return v;
    }
    uint64_t count(uint64_t limit) {
        const uint64_t n = value<uint64_t>();
        if (n > limit) {
            throw std::runtime_error("corrupt count");
        }
        return n;
    }
    ConvexVolume volume() {
        ConvexVolume v;
        v.flat = value<uint8_t>() != 0;
        const uint64_t faces = count(1 << 20);
        for (uint64_t i = 0; i < faces; ++i) {
            Polygon face;
            face.on_split_plane = value<uint64_t>();
            face.vertices.resize(count(1 << 20));
            in_.read(reinterpret_cast<char*>(face.vertices.data()),
                     std::streamsize(face.vertices.size() * sizeof(dvec3)));
            v.faces.push_back(std::move(face));
            v.planes.push_back(value<Plane>());
        }
        return v;
    }

private:
    std::istream& in_;
};

std::shared_ptr<const LocalVolumes> read_volumes(uint64_t key) {
    std::ifstream in(volumes_file(key), std::ios::binary);
    if (!in) {
        return nullptr;
    }
    try {
        Reader r(in);
        std::string version(kVolumesVersion.size(), '\0');
        in.read(version.data(), std::streamsize(version.size()));
        if (!in || version != kVolumesVersion || r.value<uint64_t>() != key) {
            return nullptr;
        }
        auto volumes = std::make_shared<LocalVolumes>();
        volumes->closed = r.value<uint8_t>() != 0;
        volumes->self_inner = r.value<uint8_t>() != 0;
        volumes->outer = r.volume();
        const uint64_t inner = r.count(1 << 10);
        for (uint64_t i = 0; i < inner; ++i) {
            volumes->automatic_inner.push_back(r.volume());
        }
        const uint64_t pieces = r.count(1 << 16);
        for (uint64_t i = 0; i < pieces; ++i) {
            LocalPiece& piece = volumes->pieces.emplace_back();
            piece.outer = r.volume();
            const uint64_t boxes = r.count(1 << 10);
            for (uint64_t k = 0; k < boxes; ++k) {
                piece.inner.push_back(r.volume());
            }
        }
        volumes->cells = r.value<int32_t>();
        volumes->empty_voxels_whole = r.value<int32_t>();
        volumes->empty_voxels_pieces = r.value<int32_t>();
        volumes->no_inner.resize(r.count(1 << 12));
        in.read(volumes->no_inner.data(), std::streamsize(volumes->no_inner.size()));
        if (!in) {
            return nullptr;
        }
        return volumes;
    } catch (const std::runtime_error&) {
        return nullptr;  // a truncated or foreign file: computed again and rewritten
    }
}

void write_volumes(uint64_t key, const LocalVolumes& volumes) {
    write_cache_file(volumes_file(key), [&](const std::filesystem::path& file) {
        std::ofstream out(file, std::ios::binary);
        Writer w(out);
        out.write(kVolumesVersion.data(), std::streamsize(kVolumesVersion.size()));
        w.value(key);
        w.value(uint8_t(volumes.closed));
        w.value(uint8_t(volumes.self_inner));
        w.volume(volumes.outer);
        w.value(uint64_t(volumes.automatic_inner.size()));
        for (const ConvexVolume& inner : volumes.automatic_inner) {
            w.volume(inner);
        }
        w.value(uint64_t(volumes.pieces.size()));
        for (const LocalPiece& piece : volumes.pieces) {
            w.volume(piece.outer);
            w.value(uint64_t(piece.inner.size()));
            for (const ConvexVolume& inner : piece.inner) {
                w.volume(inner);
            }
        }
        w.value(int32_t(volumes.cells));
        w.value(int32_t(volumes.empty_voxels_whole));
        w.value(int32_t(volumes.empty_voxels_pieces));
        w.value(uint64_t(volumes.no_inner.size()));
        out.write(volumes.no_inner.data(), std::streamsize(volumes.no_inner.size()));
        out.close();
        if (!out) {
            fail("{}: cannot write", file.string());
        }
    });
}

std::filesystem::path verified_box_file(uint64_t mesh_key, uint64_t box_key) {
    return cache_directory() / "volumes" / fmt::format("{:016x}-box-{:016x}.ok", mesh_key, box_key);
}

// The share of an object's outer volumes (its hull, or its pieces' hulls) that its automatic
// inner volumes fill: 1 where nothing between them is uncertain (a box in its own hull, a flat
// mesh that is its own inner volume). Inner volumes may overlap, which can only raise it.
double inner_fill(const LocalVolumes& local) {
    if (local.self_inner) {
        return 1.0;
    }
    double outer = 0.0, inner = 0.0;
    if (local.pieces.empty()) {
        outer = local.outer.volume();
        for (const ConvexVolume& v : local.automatic_inner) {
            inner += v.volume();
        }
    } else {
        for (const LocalPiece& piece : local.pieces) {
            outer += piece.outer.volume();
            for (const ConvexVolume& v : piece.inner) {
                inner += v.volume();
            }
        }
    }
    return outer > 0.0 ? std::min(1.0, inner / outer) : 1.0;
}

}  // namespace

uint64_t volumes_key(const Mesh& mesh, const BoundsSettings& options) {
    uint64_t hash = fnv1a(kVolumesVersion);
    hash = mix(hash, mesh.positions.data(), mesh.positions.size());
    hash = mix(hash, mesh.triangles.data(), mesh.triangles.size());
    const int32_t settings[3] = {options.max_outer_planes, options.automatic_inner ? 1 : 0,
                                 options.pieces ? 1 : 0};
    return mix(hash, settings, 3);
}

void VolumeLibrary::forget_process_volumes() {
    const std::lock_guard lock(process_mutex());
    process_volumes().clear();
}

VolumeLibrary& VolumeLibrary::shared(BoundsSettings options) {
    static std::mutex mutex;
    // Keyed by every option: a library made for one set computes its volumes with that set.
    static std::map<std::tuple<int, bool, bool>, std::unique_ptr<VolumeLibrary>> libraries;
    const std::lock_guard lock(mutex);
    std::unique_ptr<VolumeLibrary>& library =
        libraries[{options.max_outer_planes, options.automatic_inner, options.pieces}];
    if (!library) {
        library = std::make_unique<VolumeLibrary>(options);
    }
    return *library;
}

const VolumeLibrary::Entry& VolumeLibrary::entry(const std::shared_ptr<const Mesh>& mesh) {
    {
        const std::lock_guard lock(mutex_);
        if (auto it = cache_.find(mesh.get()); it != cache_.end()) {
            if (!it->second.mesh.expired()) {
                return it->second;
            }
            cache_.erase(it);
        }
    }
    const uint64_t key = volumes_key(*mesh, options_);
    std::shared_ptr<const LocalVolumes> volumes;
    bool from_disk = false, computed = false;
    if (caching_) {
        const std::lock_guard lock(process_mutex());
        if (auto it = process_volumes().find(key); it != process_volumes().end()) {
            volumes = it->second;
        }
    }
    if (!volumes && caching_) {
        volumes = read_volumes(key);
        from_disk = volumes != nullptr;
    }
    if (!volumes) {
        volumes = std::make_shared<const LocalVolumes>(compute(*mesh));
        computed = true;
        if (caching_) {
            write_volumes(key, *volumes);
        }
    }
    if (caching_) {
        const std::lock_guard lock(process_mutex());
        process_volumes().emplace(key, volumes);
    }
    const std::lock_guard lock(mutex_);
    std::erase_if(cache_, [](const auto& item) { return item.second.mesh.expired(); });
    auto [it, inserted] =
        cache_.emplace(mesh.get(), Entry{mesh, volumes, key, inner_fill(*volumes)});
    if (inserted) {
        (computed ? stats_.computed : from_disk ? stats_.disk : stats_.memory) += 1;
    }
    return it->second;
}

const LocalVolumes& VolumeLibrary::local(const std::shared_ptr<const Mesh>& mesh) {
    return *entry(mesh).volumes;
}

VolumeLibraryStats VolumeLibrary::stats() const {
    const std::lock_guard lock(mutex_);
    return stats_;
}

bool VolumeLibrary::box_verified(const Mesh& mesh, uint64_t key, const Box& box) {
    const uint64_t box_key = mix(fnv1a(kVolumesVersion), &box, 1);
    {
        const std::lock_guard lock(mutex_);
        if (verified_boxes_.contains({key, box_key})) {
            return true;
        }
    }
    std::error_code ec;
    const std::filesystem::path marker = verified_box_file(key, box_key);
    bool inside = caching_ && std::filesystem::is_regular_file(marker, ec);
    if (!inside) {
        inside = box_inside_mesh(mesh, box);
        if (inside && caching_) {
            write_cache_file(marker, [](const std::filesystem::path& file) {
                std::ofstream out(file, std::ios::binary);
                out << "inside\n";
            });
        }
    }
    if (inside) {
        const std::lock_guard lock(mutex_);
        verified_boxes_.insert({key, box_key});
    }
    return inside;
}

namespace {

// The object has no inner volume: none given, and none found in its mesh.
bool lacks_inner(const Object& object, const LocalVolumes& local) {
    return object.inner_boxes.empty() && !local.self_inner && !local.no_inner.empty();
}

}  // namespace

ExactOccluders exact_occluders(const std::vector<ObjectVolumes>& volumes) {
    ExactOccluders out;
    for (const ObjectVolumes& v : volumes) {
        if (!v.triangles.empty()) {
            out.triangles += v.mesh_triangles;
            out.polygons += v.triangles.size();
            out.list.push_back({v.name, v.mesh_triangles, v.why_triangles});
        }
    }
    return out;
}

std::string missing_inner_summary(const std::vector<MissingInner>& missing, size_t objects) {
    if (missing.empty()) {
        return {};
    }
    std::map<std::string, size_t> by_reason;
    for (const MissingInner& m : missing) {
        ++by_reason[m.reason];
    }
    std::vector<std::pair<size_t, std::string>> reasons;
    for (const auto& [reason, count] : by_reason) {
        reasons.emplace_back(count, reason);
    }
    std::stable_sort(reasons.begin(), reasons.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    std::string line = fmt::format("{} of {} objects {} no automatic inner volume", missing.size(),
                                   objects, missing.size() == 1 ? "has" : "have");
    for (size_t i = 0; i < reasons.size(); ++i) {
        line += fmt::format("{} {} because {}", i == 0 ? ":" : ";", reasons[i].first,
                            reasons[i].second);
    }
    return line;
}

void VolumeLibrary::compute_missing(const Scene& scene) {
    // The meshes not seen before, computed in parallel (each is independent of the others),
    // then cached in scene order.
    std::vector<std::shared_ptr<const Mesh>> missing;
    {
        const std::lock_guard lock(mutex_);
        std::set<const Mesh*> seen;
        for (const Object& object : scene.objects) {
            if (!cache_.contains(object.mesh.get()) && seen.insert(object.mesh.get()).second) {
                missing.push_back(object.mesh);
            }
        }
    }
    // Hulls and pieces of a large model take seconds (cached afterwards): said so.
    Progress progress(
        fmt::format("bounding volumes of {} meshes (computed once, then cached)", missing.size()),
        missing.size());
    tbb::parallel_for(size_t(0), missing.size(), [&](size_t i) {
        entry(missing[i]);
        progress.advance();
    });
}

void VolumeLibrary::append_volumes(const Object& object, int index,
                                   std::vector<ObjectVolumes>& result) {
    const Entry& entry = this->entry(object.mesh);
    const LocalVolumes& local = *entry.volumes;
    const glm::dmat4 transform(object.transform);
    std::vector<ConvexVolume> explicit_inner;
    for (size_t b = 0; b < object.inner_boxes.size(); ++b) {
        if (!box_verified(*object.mesh, entry.key, object.inner_boxes[b])) {
            fail("object '{}': inner box {} is not strictly inside its mesh", object.name, b);
        }
        explicit_inner.push_back(box_volume(object.inner_boxes[b]).transformed(transform));
    }
    if (local.pieces.empty()) {
        ObjectVolumes volumes;
        volumes.object = index;
        volumes.name = object.name;
        volumes.outer = local.outer.transformed(transform);
        if (!object.inner_boxes.empty()) {
            volumes.inner = explicit_inner;
        } else if (local.self_inner) {
            volumes.inner.push_back(volumes.outer);
        } else {
            for (const ConvexVolume& inner : local.automatic_inner) {
                volumes.inner.push_back(inner.transformed(transform));
            }
        }
        result.push_back(std::move(volumes));
        return;
    }
    for (size_t p = 0; p < local.pieces.size(); ++p) {
        ObjectVolumes volumes;
        volumes.object = index;
        volumes.name = object.name;
        volumes.piece = int(p);
        volumes.pieces = int(local.pieces.size());
        volumes.outer = local.pieces[p].outer.transformed(transform);
        if (object.inner_boxes.empty()) {
            for (const ConvexVolume& inner : local.pieces[p].inner) {
                volumes.inner.push_back(inner.transformed(transform));
            }
        } else if (p == 0) {
            volumes.inner = explicit_inner;  // the object's boxes go with its first piece
        }
        result.push_back(std::move(volumes));
    }
}

std::vector<std::string> VolumeLibrary::exact_objects(const Scene& scene) {
    const BoundsSettings& b = scene.bounds;
    std::vector<std::string> exact(scene.objects.size());
    if (b.occluders == Occluders::volumes) {
        return exact;
    }
    // auto: first the objects without an inner volume (all behind their hulls is uncertain),
    // then the loose ones (inner volumes filling less than min_inner_fill of the outer ones:
    // explicit inner boxes are the author's word and stay), each group smallest first, within
    // the triangle budget.
    struct Candidate {
        int group;  // 0 no inner volume, 1 loose
        size_t triangles, object;
        std::string why;
    };
    std::vector<Candidate> candidates;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& object = scene.objects[i];
        if (!scene.casts_shadow(object)) {
            continue;
        }
        if (b.occluders == Occluders::triangles) {
            exact[i] = "occluders = triangles";
            continue;
        }
        const Entry& e = entry(object.mesh);
        const LocalVolumes& local = *e.volumes;
        const size_t triangles = object.mesh->triangles.size();
        if (lacks_inner(object, local)) {
            candidates.push_back(
                {0, triangles, i, fmt::format("no inner volume ({})", local.no_inner)});
        } else if (const double fill = e.inner_fill;
                   object.inner_boxes.empty() && fill < b.min_inner_fill) {
            candidates.push_back(
                {1, triangles, i,
                 fmt::format("loose: inner volumes fill {:.0f} % of its {} (min_inner_fill {:g})",
                             100.0 * fill, local.pieces.empty() ? "hull" : "pieces",
                             b.min_inner_fill)});
        }
    }
    std::stable_sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) {
        return std::tie(x.group, x.triangles) < std::tie(y.group, y.triangles);
    });
    size_t total = 0;
    for (Candidate& c : candidates) {
        if (total + c.triangles > size_t(b.max_triangles)) {
            continue;  // a smaller one may still fit
        }
        total += c.triangles;
        exact[c.object] = std::move(c.why);
    }
    return exact;
}

std::shared_ptr<const VolumeLibrary::MeshSurface> VolumeLibrary::surface_of(
    const std::shared_ptr<const Mesh>& mesh) {
    {
        const std::lock_guard lock(mutex_);
        if (auto it = surfaces_.find(mesh.get()); it != surfaces_.end()) {
            if (!it->second.first.expired()) {
                return it->second.second;
            }
            surfaces_.erase(it);
        }
    }
    auto surface = std::make_shared<const MeshSurface>(
        MeshSurface{closed_surface(*mesh), coplanar_faces(*mesh)});
    const std::lock_guard lock(mutex_);
    surfaces_[mesh.get()] = {mesh, surface};
    return surface;
}

ObjectVolumes VolumeLibrary::triangles_of(const Object& object, int index) {
    const glm::dmat4 transform(object.transform);
    ObjectVolumes volumes;
    volumes.object = index;
    volumes.name = object.name;
    const Mesh& mesh = *object.mesh;
    const std::shared_ptr<const MeshSurface> surface = surface_of(object.mesh);
    volumes.closed = surface->closed.whole();
    const bool some_closed = surface->closed.usable();
    volumes.mesh_triangles = mesh.triangles.size();
    // A mirroring transform turns every winding.
    const int8_t mirrored = glm::determinant(glm::dmat3(transform)) < 0.0 ? -1 : 1;
    const CoplanarFaces& faces = surface->faces;
    volumes.triangles.reserve(faces.faces.size());
    volumes.face_planes.reserve(faces.faces.size());
    volumes.face_balls.reserve(faces.faces.size());
    volumes.face_bounds = {dvec3(std::numeric_limits<double>::max()),
                           dvec3(std::numeric_limits<double>::lowest())};
    for (size_t f = 0; f < faces.faces.size(); ++f) {
        std::vector<dvec3> corners;
        corners.reserve(faces.faces[f].size());
        for (const uint32_t k : faces.faces[f]) {
            corners.emplace_back(transform * glm::dvec4(dvec3(mesh.positions[k]), 1.0));
        }
        // A face's triangles lie on one component (they share edges), so its first one's side is
        // the face's.
        const int8_t outward = some_closed ? surface->closed.outward[faces.triangle[f]] : 0;
        if (outward * mirrored < 0) {
            std::reverse(corners.begin(), corners.end());  // wound outward in the world
        }
        Plane plane;
        if (!Plane::through(corners[0], corners[1], corners[2], plane)) {
            plane.normal = dvec3(0.0);
        }
        volumes.face_planes.push_back(plane);
        for (const dvec3& corner : corners) {
            volumes.face_bounds.first = glm::min(volumes.face_bounds.first, corner);
            volumes.face_bounds.second = glm::max(volumes.face_bounds.second, corner);
        }
        volumes.triangles.emplace_back(std::move(corners));
        volumes.face_balls.push_back(bounding_ball(volumes.triangles.back()));
        if (some_closed) {
            volumes.closed_faces.push_back(outward != 0);
        }
    }
    if (volumes.triangles.size() > kFacesPerCluster) {
        volumes.clusters = cluster_faces(volumes.triangles, kFacesPerCluster);
    }
    return volumes;
}

std::vector<ObjectVolumes> VolumeLibrary::build(const Scene& scene,
                                                std::vector<MissingInner>* missing) {
    if (scene.bounds.occluders != Occluders::triangles) {
        compute_missing(scene);  // every object as its triangles needs no volume
    }
    std::vector<std::string> exact = exact_objects(scene);
    std::vector<ObjectVolumes> result;
    for (size_t i = 0; i < scene.objects.size(); ++i) {
        const Object& object = scene.objects[i];
        if (!scene.casts_shadow(object)) {
            continue;  // glass: the light passes it
        }
        if (!exact[i].empty()) {
            result.push_back(triangles_of(object, int(i)));
            result.back().why_triangles = std::move(exact[i]);
            continue;  // exact: it needs no inner volume
        }
        append_volumes(object, int(i), result);
        const LocalVolumes& local = *entry(object.mesh).volumes;
        if (lacks_inner(object, local) && options_.automatic_inner && missing) {
            missing->push_back({object.name, local.no_inner});
        }
    }
    return result;
}

VolumeLibrary::SceneState VolumeLibrary::state_of(const Scene& scene) {
    SceneState state{
        {}, scene.bounds.occluders, scene.bounds.max_triangles, scene.bounds.min_inner_fill};
    state.parts.reserve(scene.objects.size());
    for (const Object& object : scene.objects) {
        state.parts.push_back({object.name, object.mesh, object.transform, object.inner_boxes,
                               scene.casts_shadow(object)});
    }
    return state;
}

std::shared_ptr<const std::vector<ObjectVolumes>> VolumeLibrary::build_shared(const Scene& scene) {
    if (!caching_) {
        return std::make_shared<const std::vector<ObjectVolumes>>(build(scene, nullptr));
    }
    SceneState state = state_of(scene);
    {
        const std::lock_guard lock(mutex_);
        if (last_volumes_ && state == last_state_) {
            return last_volumes_;
        }
    }
    auto volumes = std::make_shared<const std::vector<ObjectVolumes>>(build(scene, nullptr));
    const std::lock_guard lock(mutex_);
    last_state_ = std::move(state);
    last_volumes_ = volumes;
    return volumes;
}

}  // namespace sl::bt
