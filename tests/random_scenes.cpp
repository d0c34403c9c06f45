#include "tests/random_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "scenes/scene_file.h"

namespace sl::test {

double uniform(std::mt19937& rng, double lo, double hi) {
    return lo + (hi - lo) * double(rng() >> 5) * (1.0 / 134217728.0);
}

dvec3 random_unit(std::mt19937& rng) {
    for (;;) {
        const dvec3 v(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
        const double l = glm::length(v);
        if (l > 0.1 && l <= 1.0) {
            return v / l;
        }
    }
}

bt::Polygon random_convex_polygon(std::mt19937& rng, const dvec3& center, double radius) {
    // Points on a circle at increasing angles: convex, counter-clockwise around `normal`.
    const dvec3 normal = random_unit(rng);
    const dvec3 u = glm::normalize(
        glm::cross(normal, std::abs(normal.x) < 0.9 ? dvec3(1, 0, 0) : dvec3(0, 1, 0)));
    const dvec3 v = glm::cross(normal, u);
    const int n = 3 + int(rng() % 8);
    std::vector<double> angles;
    for (int i = 0; i < n; ++i) {
        angles.push_back(uniform(rng, 0, 2 * M_PI));
    }
    std::sort(angles.begin(), angles.end());
    std::vector<dvec3> vertices;
    for (const double a : angles) {
        vertices.push_back(center + radius * (std::cos(a) * u + std::sin(a) * v));
    }
    return bt::Polygon(vertices);
}

// Splitting a convex polygon by a plane conserves its area, and each side lies on its side.
ShapeMeshes::ShapeMeshes() {
    Mesh mesh = load_mesh(SceneSearchPaths::defaults().data / "meshes" / "bunny00.off");
    fit_mesh(mesh, 1.0f);
    bunny = std::make_shared<const Mesh>(std::move(mesh));
}

ShapeMeshes& shapes() {
    static ShapeMeshes s;
    return s;
}

Object make_object(const std::string& name, std::shared_ptr<const Mesh> mesh,
                   const glm::mat4& transform) {
    Object object;
    object.name = name;
    object.mesh = std::move(mesh);
    object.transform = transform;
    return object;
}

// A wall in x, y ∈ [-1, 1], z ∈ [-t, t] with one to three rectangular openings, as exporters
// write it: front and back cut into a grid of quads around the openings (T-junctions where the
// reveals meet them); the reveals or a side of the rim sometimes missing (an open mesh).
std::shared_ptr<const Mesh> random_wall(std::mt19937& rng) {
    const double t = uniform(rng, 0.05, 0.25);
    std::vector<std::array<double, 4>> holes;  // x0, x1, y0, y1
    const int wanted = 1 + int(rng() % 3);
    for (int attempt = 0; attempt < 50 && int(holes.size()) < wanted; ++attempt) {
        const double w = uniform(rng, 0.2, 0.8), h = uniform(rng, 0.2, 1.2);
        const double x = uniform(rng, -0.9, 0.9 - w), y = uniform(rng, -0.9, 0.9 - h);
        const std::array<double, 4> hole{x, x + w, y, y + h};
        bool apart = true;
        for (const auto& o : holes) {
            apart &= hole[1] + 0.05 < o[0] || o[1] + 0.05 < hole[0] || hole[3] + 0.05 < o[2] ||
                     o[3] + 0.05 < hole[2];
        }
        if (apart) {
            holes.push_back(hole);
        }
    }
    std::vector<double> xs{-1, 1}, ys{-1, 1};
    for (const auto& hole : holes) {
        xs.insert(xs.end(), {hole[0], hole[1]});
        ys.insert(ys.end(), {hole[2], hole[3]});
    }
    std::sort(xs.begin(), xs.end());
    std::sort(ys.begin(), ys.end());
    MeshBuilder b;
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
        for (size_t j = 0; j + 1 < ys.size(); ++j) {
            const double cx = 0.5 * (xs[i] + xs[i + 1]), cy = 0.5 * (ys[j] + ys[j + 1]);
            bool open = false;
            for (const auto& hole : holes) {
                open |= hole[0] < cx && cx < hole[1] && hole[2] < cy && cy < hole[3];
            }
            if (!open) {
                const double x0 = xs[i], x1 = xs[i + 1], y0 = ys[j], y1 = ys[j + 1];
                b.quad({x0, y0, t}, {x1, y0, t}, {x1, y1, t}, {x0, y1, t});
                b.quad({x0, y0, -t}, {x0, y1, -t}, {x1, y1, -t}, {x1, y0, -t});
            }
        }
    }
    const bool reveals = rng() % 3 != 0;
    for (const auto& [x0, x1, y0, y1] : holes) {
        if (reveals) {  // facing into the opening
            b.quad({x1, y0, -t}, {x1, y0, t}, {x1, y1, t}, {x1, y1, -t});
            b.quad({x0, y0, -t}, {x0, y1, -t}, {x0, y1, t}, {x0, y0, t});
            b.quad({x0, y1, -t}, {x1, y1, -t}, {x1, y1, t}, {x0, y1, t});
            b.quad({x0, y0, -t}, {x0, y0, t}, {x1, y0, t}, {x1, y0, -t});
        }
    }
    // The rim: the box's x and y faces.
    b.box(glm::dmat4(1.0), dvec3(-1, -1, -t), dvec3(1, 1, t),
          0b110000u | (rng() % 4 == 0 ? 1u << (rng() % 4) : 0u));
    return b.finish(rng() % 5 == 0);
}

// Two or three boxes in one mesh, apart, touching or overlapping; sometimes one open.
std::shared_ptr<const Mesh> random_parts(std::mt19937& rng) {
    MeshBuilder b;
    const int parts = 2 + int(rng() % 2);
    for (int k = 0; k < parts; ++k) {
        glm::dmat4 m = glm::translate(
            glm::dmat4(1.0),
            dvec3(uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6), uniform(rng, -0.6, 0.6)));
        if (rng() % 2) {
            m = glm::rotate(m, uniform(rng, 0, 6.3), random_unit(rng));
        }
        const dvec3 half(uniform(rng, 0.1, 0.4), uniform(rng, 0.1, 0.4), uniform(rng, 0.1, 0.4));
        b.box(m, -half, half, rng() % 4 == 0 ? 1u << (rng() % 6) : 0u);
    }
    return b.finish(rng() % 5 == 0);
}

// A box with one to three faces missing: a shelf, a hood, a room without a ceiling.
std::shared_ptr<const Mesh> random_open_box(std::mt19937& rng) {
    MeshBuilder b;
    unsigned skip = 0;
    for (int k = 1 + int(rng() % 3); k > 0; --k) {
        skip |= 1u << (rng() % 6);
    }
    b.box(glm::dmat4(1.0), dvec3(-0.5), dvec3(0.5), skip);
    return b.finish(rng() % 2 == 0);
}

// A height field over [-1, 1]²: an open, non-convex surface (terrain, cloth), `n` quads a side
// (4 to 9 when 0); wound so that its normals face +y, or -y when `inside_out`.
std::shared_ptr<const Mesh> random_terrain(std::mt19937& rng, int n, bool inside_out) {
    n = n > 0 ? n : 4 + int(rng() % 6);
    std::vector<double> height((n + 1) * (n + 1));
    for (double& h : height) {
        h = uniform(rng, -0.4, 0.4);
    }
    auto at = [&](int i, int j) {
        return dvec3(-1.0 + 2.0 * i / n, height[size_t(j * (n + 1) + i)], -1.0 + 2.0 * j / n);
    };
    MeshBuilder b;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            b.quad(at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
        }
    }
    return b.finish(inside_out);
}

// A random spot light looking down (its axis within 35 degrees of -y); returns the axis.
dvec3 random_light(std::mt19937& rng, SpotLight& light) {
    light.position = glm::vec3(uniform(rng, -2, 2), uniform(rng, 2, 5), uniform(rng, -2, 2));
    const dvec3 axis =
        glm::normalize(dvec3(uniform(rng, -0.7, 0.7), -1.0, uniform(rng, -0.7, 0.7)));
    light.target = light.position + glm::vec3(5.0 * axis);
    light.cone_half_angle_degrees = float(uniform(rng, 15, 55));
    light.near = float(uniform(rng, 0.05, 0.8));
    light.far = float(uniform(rng, 6, 12));
    return axis;
}

// An object's centre: in the light's cone, or (`around_light`, half the time) anywhere 0.8 to
// 3 m from the light.
dvec3 random_center(std::mt19937& rng, const SpotLight& light, const dvec3& axis,
                    bool around_light) {
    if (around_light && rng() % 2) {
        return dvec3(light.position) + uniform(rng, 0.8, 3.0) * random_unit(rng);
    }
    const double spread = std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    const double depth = uniform(rng, 1.0, 0.9 * light.far);
    const dvec3 lateral = random_unit(rng) * uniform(rng, 0, spread * depth);
    return dvec3(light.position) + depth * axis + lateral - glm::dot(lateral, axis) * axis;
}

// The open kinds (6 to 12 of random_scenes.h's Shapes: walls, parts, open boxes, terrain, a
// room around the light): the object's mesh, its placement changed where the kind needs.
void open_object(std::mt19937& rng, int kind, int seed, const dvec3& center, double size,
                 const SpotLight& light, Object& object, glm::mat4& transform) {
    switch (kind) {
        case 12: {
            object.mesh = random_terrain(rng, 4 + int(rng() % 6), seed % 2 == 0);
            transform = glm::translate(glm::mat4(1.0f), glm::vec3(center));
            transform =
                glm::rotate(transform, float(uniform(rng, 0, 6.3)), glm::vec3(0.0f, 1.0f, 0.0f));
            transform = glm::rotate(transform, float(glm::radians(uniform(rng, 0, 35))),
                                    glm::vec3(1.0f, 0.0f, 0.0f));
            transform = glm::scale(transform, glm::vec3(2.0 * size));
            break;
        }
        case 6:
            object.mesh = random_wall(rng);
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 7:
            object.mesh = random_parts(rng);
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 8:
            object.mesh = random_open_box(rng);
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 9:
            object.mesh = random_terrain(rng);
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 10:
            object.mesh = shapes().torus;
            transform = glm::scale(transform, glm::vec3(2.0 * size));
            break;
        case 11: {
            // A room around the light: a large open box (often without a floor), the
            // light off its centre.
            object.mesh = random_open_box(rng);
            const glm::vec3 offset(uniform(rng, -0.2, 0.2), uniform(rng, -0.2, 0.2),
                                   uniform(rng, -0.2, 0.2));
            transform = glm::translate(glm::mat4(1.0f), light.position + offset);
            transform = glm::scale(transform, glm::vec3(float(uniform(rng, 2.5, 6.0))));
            break;
        }
    }
}

// The closed kinds (0 to 5: box, sphere, torus, bunny, plane, boxes sharing a face): the
// object's mesh and placement, and the objects that go with it.
void closed_object(std::mt19937& rng, int kind, const dvec3& center, double size,
                   const SpotLight& light, Object& object, glm::mat4& transform,
                   std::vector<Object>& extra) {
    switch (kind) {
        case 0:
            object.mesh = shapes().box;
            transform = glm::scale(transform, glm::vec3(size * uniform(rng, 0.4, 1.0), size,
                                                        size * uniform(rng, 0.4, 1.6)));
            if (rng() % 2)
                object.inner_boxes = {{glm::vec3(-0.4f), glm::vec3(0.4f)}};
            break;
        case 1:
            object.mesh = shapes().sphere;
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 2:
            object.mesh = shapes().torus;
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 3:
            object.mesh = shapes().bunny;
            transform = glm::scale(transform, glm::vec3(size));
            break;
        case 4: {
            object.mesh = shapes().plane;
            if (rng() % 2) {
                // Edge-on: the plane's normal is perpendicular to the direction to the
                // light.
                const dvec3 to_light = glm::normalize(dvec3(light.position) - center);
                const dvec3 normal = glm::normalize(glm::cross(to_light, random_unit(rng)));
                const dvec3 tangent = glm::cross(normal, to_light);
                glm::dmat4 m(1.0);
                m[0] = glm::dvec4(to_light, 0.0);
                m[1] = glm::dvec4(normal, 0.0);
                m[2] = glm::dvec4(tangent, 0.0);
                m[3] = glm::dvec4(center, 1.0);
                transform = glm::mat4(m);
            }
            transform = glm::scale(transform, glm::vec3(2.0 * size, 1.0, 2.0 * size));
            break;
        }
        default: {
            // Two boxes sharing a face (coplanar faces), overlapping a third.
            object.mesh = shapes().box;
            transform = glm::scale(transform, glm::vec3(size));
            extra = {make_object("twin", shapes().box,
                                 glm::translate(transform, glm::vec3(1.0f, 0.0f, 0.0f))),
                     make_object("overlap", shapes().box,
                                 glm::scale(glm::translate(transform, glm::vec3(0.5f, 0.4f, 0.3f)),
                                            glm::vec3(0.9f)))};
            break;
        }
    }
}

// The object(s) of one kind at `center`, of about `size`, placed by `transform` (a random
// rotation about the centre, which some kinds replace); the first is the object, the rest go
// with it.
std::vector<Object> random_object(std::mt19937& rng, int kind, int seed, const dvec3& center,
                                  double size, glm::mat4 transform, const SpotLight& light) {
    Object object;
    std::vector<Object> extra;
    if (kind >= 6) {
        open_object(rng, kind, seed, center, size, light, object, transform);
    } else {
        closed_object(rng, kind, center, size, light, object, transform, extra);
    }
    object.transform = transform;
    extra.insert(extra.begin(), object);
    return extra;
}

// Whether an outer volume (a hull, or a piece's) of any of the objects holds the light.
bool holds_light(bt::VolumeLibrary& library, const std::vector<Object>& objects,
                 const SpotLight& light) {
    bool contains_light = false;
    for (const Object& o : objects) {
        const bt::LocalVolumes& local = library.local(o.mesh);
        auto holds = [&](const bt::ConvexVolume& outer) {
            return outer.transformed(glm::dmat4(o.transform))
                .contains(dvec3(light.position), -1e-3);
        };
        contains_light |= local.pieces.empty() && holds(local.outer);
        for (const bt::LocalPiece& piece : local.pieces) {
            contains_light |= holds(piece.outer);
        }
    }
    return contains_light;
}

// On every fourth seed about half the objects hang around the light rather than in its cone
// (random_scenes.h says what each Shapes holds).
RandomScene random_scene(int seed, bt::VolumeLibrary& library, Shapes kinds) {
    std::mt19937 rng(seed);
    RandomScene result;
    Scene& scene = result.scene;
    const dvec3 axis = random_light(rng, scene.light);
    const bool around_light = seed % 4 == 0;
    const int count = 1 + int(rng() % 7);
    for (int i = 0; i < count; ++i) {
        for (int attempt = 0; attempt < 20; ++attempt) {
            const dvec3 center = random_center(rng, scene.light, axis, around_light);
            const double size = uniform(rng, 0.3, 1.6);
            glm::mat4 transform = glm::translate(glm::mat4(1.0f), glm::vec3(center));
            transform =
                glm::rotate(transform, float(uniform(rng, 0, 6.3)), glm::vec3(random_unit(rng)));
            const int kind =
                kinds == Shapes::terrain ? 12 : int(rng() % 6) + (kinds == Shapes::real ? 6 : 0);
            std::vector<Object> objects =
                random_object(rng, kind, seed, center, size, transform, scene.light);
            objects.front().name = fmt::format("object{}-kind{}", i, kind);
            if (holds_light(library, objects, scene.light)) {
                continue;
            }
            for (Object& o : objects) {
                scene.objects.push_back(std::move(o));
            }
            result.kinds += fmt::format("{} ", kind);
            break;
        }
    }
    return result;
}

dvec3 random_point(std::mt19937& rng, const SpotLight& light) {
    const dvec3 d = glm::normalize(dvec3(light.direction()));
    const dvec3 u = glm::normalize(dvec3(light.up()) - glm::dot(dvec3(light.up()), d) * d);
    const dvec3 r = glm::cross(d, u);
    if (light.parallel()) {  // in the box, up to 5% beyond its sides and far end; or anywhere
        const double w = double(light.half_width);
        if (rng() % 8 == 0) {
            return dvec3(light.position) + (double(light.far) + w) * dvec3(uniform(rng, -1, 1),
                                                                           uniform(rng, -1, 1),
                                                                           uniform(rng, -1, 1));
        }
        return dvec3(light.position) + uniform(rng, 0.0, 1.05 * light.far) * d +
               uniform(rng, -1.05, 1.05) * w * r + uniform(rng, -1.05, 1.05) * w * u;
    }
    const double spread = std::tan(glm::radians(double(light.cone_half_angle_degrees)));
    if (rng() % 8 == 0) {  // anywhere around, mostly outside the influence volume
        return dvec3(light.position) + double(light.far) * dvec3(uniform(rng, -1, 1),
                                                                 uniform(rng, -1, 1),
                                                                 uniform(rng, -1, 1));
    }
    const double depth = uniform(rng, 0.0, 1.05 * light.far);
    return dvec3(light.position) + depth * (d + uniform(rng, -1.05, 1.05) * spread * r +
                                            uniform(rng, -1.05, 1.05) * spread * u);
}

}  // namespace sl::test
