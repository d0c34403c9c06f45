#include "methods/regions_summary.h"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "analytic/in_scattering.h"

namespace sl::methods {

using glm::dvec3;

std::array<double, 3> eye_ray_lengths(const Scene& scene, const bt::BeamTree& tree,
                                      const std::vector<float>& depth, int width, int height) {
    const PixelUnprojector pixels(scene.camera, width, height);
    std::array<double, 3> lengths{};
    std::vector<bt::RegionInterval> intervals;
    for (int y = 0; y < height; y += 2) {
        for (int x = 0; x < width; x += 2) {
            const double ndc = 2.0 * double(depth[size_t(y) * size_t(width) + size_t(x)]) - 1.0;
            const dvec3 origin = pixels.point(x, y, -1.0);
            const dvec3 end = pixels.point(x, y, std::min(ndc, 1.0));
            const double length = glm::length(end - origin);
            if (!(length > 0.0)) {
                continue;
            }
            const analytic::EyeRay ray{origin, (end - origin) / length};
            const analytic::Interval cone = analytic::light_interval(ray, scene.light, length);
            if (cone.empty()) {
                continue;
            }
            intervals.clear();
            tree.trace(ray.origin, ray.direction, cone.begin, cone.end, intervals);
            for (const bt::RegionInterval& interval : intervals) {
                lengths[size_t(interval.region)] += interval.end - interval.begin;
            }
        }
    }
    return lengths;
}

std::map<int, int> objects_by_pieces(const std::vector<bt::ObjectVolumes>& volumes) {
    std::map<int, int> pieces_of;
    for (const bt::ObjectVolumes& v : volumes) {
        if (v.triangles.empty()) {  // exact occluders are no pieces
            pieces_of[v.object] = v.pieces;
        }
    }
    std::map<int, int> objects;
    for (const auto& [object, count] : pieces_of) {
        ++objects[count];
    }
    return objects;
}

namespace {

double eye_share(const RegionsSummaryInputs& in, bt::Region region) {
    const double total = in.eye_lengths[0] + in.eye_lengths[1] + in.eye_lengths[2];
    return total > 0.0 ? in.eye_lengths[size_t(region)] / total : 0.0;
}

Row region_json(const bt::Regions& regions, bt::Region region) {
    return {{"pieces", regions.pieces[size_t(region)].size()},
            {"faces", regions.face_count(region)},
            {"volume", regions.volume[size_t(region)]}};
}

}  // namespace

Row regions_summary_json(const RegionsSummaryInputs& in) {
    Row pieces_json = Row::object();
    for (const auto& [count, objects] : objects_by_pieces(in.volumes)) {
        pieces_json[std::to_string(count)] = objects;
    }
    const bt::BeamTreeStats stats = in.tree.stats();
    Row warnings = Row::array(), missing = Row::array();
    if (const std::string summary =
            bt::missing_inner_summary(in.missing_inner, in.scene.objects.size());
        !summary.empty()) {
        warnings.push_back(summary);
    }
    for (const bt::MissingInner& m : in.missing_inner) {
        missing.push_back({{"object", m.object}, {"reason", m.reason}});
    }
    Row as_triangles = Row::array();
    for (const bt::ExactOccluders::Object& o : bt::exact_occluders(in.volumes).list) {
        as_triangles.push_back({{"object", o.name}, {"triangles", o.triangles}, {"why", o.why}});
    }
    size_t inner_volumes = 0, outer_faces = 0;
    for (const bt::ObjectVolumes& v : in.volumes) {
        inner_volumes += v.inner.size();
        outer_faces += v.outer.faces.size();
    }
    const RegionsTimings& t = in.timings;
    return {
        {"scene", in.scene.name},
        {"epsilon", in.tree.epsilon()},
        {"objects", in.scene.objects.size()},
        {"outer_volume_faces", outer_faces},
        {"outer_volumes", in.volumes.size()},
        {"objects_by_pieces", pieces_json},
        {"eye_ray_share",
         {{"lit", eye_share(in, bt::Region::lit)},
          {"uncertain", eye_share(in, bt::Region::uncertain)},
          {"unlit", eye_share(in, bt::Region::unlit)},
          {"length", in.eye_lengths[0] + in.eye_lengths[1] + in.eye_lengths[2]}}},
        {"inner_volumes", inner_volumes},
        {"max_outer_planes", in.max_outer_planes},
        {"beams", in.regions.beam_count},
        {"tree",
         {{"nodes", stats.nodes},
          {"max_depth", stats.max_depth},
          {"open_leaves", stats.open_leaves},
          {"solid_leaves", stats.solid_leaves},
          {"blocker_leaves", stats.blocker_leaves},
          {"outer_polygons", stats.outer_polygons},
          {"stopper_polygons", stats.stopper_polygons},
          {"exact_polygons", stats.exact_polygons},
          {"hidden_polygons", stats.hidden_polygons}}},
        {"regions",
         {{"lit", region_json(in.regions, bt::Region::lit)},
          {"uncertain", region_json(in.regions, bt::Region::uncertain)},
          {"unlit", region_json(in.regions, bt::Region::unlit)}}},
        {"influence_volume", in.regions.influence_volume},
        {"volumes_ms", t.volumes_ms},
        {"build_ms", t.build_ms},
        {"extract_ms", t.extract_ms},
        {"render_ms", t.render_ms},
        {"picture_ms", t.picture_ms},
        {"warnings", warnings},
        {"objects_without_inner_volume", missing},
        {"occluders", to_string(in.scene.bounds.occluders)},
        {"objects_as_triangles", as_triangles},
    };
}

std::string regions_summary_text(const RegionsSummaryInputs& in, double write_ms,
                                 const std::string& out) {
    const std::map<int, int> by_pieces = objects_by_pieces(in.volumes);
    std::string pieces;
    for (const auto& [count, objects] : by_pieces) {
        pieces += fmt::format("{}{} x {}", pieces.empty() ? "" : ", ", objects, count);
    }
    const bt::ExactOccluders exact = bt::exact_occluders(in.volumes);
    const size_t exact_objects = exact.list.size(), exact_triangles = exact.triangles;
    const int casting =
        std::accumulate(by_pieces.begin(), by_pieces.end(), int(exact_objects),
                        [](int sum, const auto& entry) { return sum + entry.second; });
    const size_t piece_count = in.volumes.size() - exact_objects;
    std::string objects =
        piece_count == 0 && exact_objects > 0
            ? std::string()
            : fmt::format(" in {} convex pieces ({} objects x pieces)", piece_count, pieces);
    if (exact_objects > 0) {
        objects +=
            fmt::format("{} {} objects as {} exact triangles in {} coplanar faces (occluders = {})",
                        objects.empty() ? ":" : ";", exact_objects, exact_triangles, exact.polygons,
                        to_string(in.scene.bounds.occluders));
    }
    const bt::Regions& r = in.regions;
    const RegionsTimings& t = in.timings;
    return fmt::format(
               "{}: {} objects casting shadows{}; eye rays in the cone: {:.1f}% lit, {:.1f}% "
               "uncertain, {:.1f}% unlit\n",
               in.scene.name, casting, objects, 100.0 * eye_share(in, bt::Region::lit),
               100.0 * eye_share(in, bt::Region::uncertain),
               100.0 * eye_share(in, bt::Region::unlit)) +
           fmt::format(
               "{}: {} beams ({} lit, {} uncertain, {} unlit pieces); volumes {:.0f} ms, tree "
               "{:.0f} ms, regions {:.0f} ms, scene render {:.0f} ms, picture {:.0f} ms, files "
               "{:.0f} ms -> {}/regions.{{ply,json,png}}\n",
               in.scene.name, r.beam_count, r.pieces[0].size(), r.pieces[1].size(),
               r.pieces[2].size(), t.volumes_ms, t.build_ms, t.extract_ms, t.render_ms,
               t.picture_ms, write_ms, out);
}

}  // namespace sl::methods
