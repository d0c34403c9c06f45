#include "ibl/cube_map.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "core/error.h"

namespace sl::ibl {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// The area element of the cube face z = 1 integrated from the face centre to (a, b):
// ∫∫ (1 + a² + b²)^(-3/2) da db = atan2(ab, sqrt(a² + b² + 1)).
double face_area(double a, double b) {
    return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0));
}

}  // namespace

CubeMap::CubeMap(int face_size) : size(face_size) {
    if (face_size <= 0 || face_size > 16384) {
        fail("cube map face size {} must be in 1..16384", face_size);
    }
    for (Image& face : faces) {
        face = Image(face_size, face_size);
    }
}

glm::vec3 CubeMap::direction(int face, int x, int y) const {
    return cube_direction(face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
}

glm::vec3 CubeMap::sample(glm::vec3 d) const {
    const CubeCoordinates c = cube_coordinates(d);
    const float px = c.st.x * float(size) - 0.5f, py = c.st.y * float(size) - 0.5f;
    const float x_floor = std::floor(px), y_floor = std::floor(py);
    const int x0 = int(x_floor), y0 = int(y_floor);
    const float fx = px - x_floor, fy = py - y_floor;
    if (x0 >= 0 && y0 >= 0 && x0 + 1 < size && y0 + 1 < size) {
        const Image& face = faces[size_t(c.face)];
        return (face.at(x0, y0) * (1.0f - fx) + face.at(x0 + 1, y0) * fx) * (1.0f - fy) +
               (face.at(x0, y0 + 1) * (1.0f - fx) + face.at(x0 + 1, y0 + 1) * fx) * fy;
    }
    // Seamless at face edges, as GL_TEXTURE_CUBE_MAP_SEAMLESS: a tap beyond the face is the texel
    // of the neighbouring face that its (extrapolated) centre direction falls on.
    auto tap = [&](int x, int y) {
        if (x >= 0 && y >= 0 && x < size && y < size) {
            return texel(c.face, x, y);
        }
        const CubeCoordinates n = cube_coordinates(cube_direction(
            c.face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)}));
        return texel(n.face, std::clamp(int(n.st.x * float(size)), 0, size - 1),
                     std::clamp(int(n.st.y * float(size)), 0, size - 1));
    };
    return (tap(x0, y0) * (1.0f - fx) + tap(x0 + 1, y0) * fx) * (1.0f - fy) +
           (tap(x0, y0 + 1) * (1.0f - fx) + tap(x0 + 1, y0 + 1) * fx) * fy;
}

CubeCoordinates cube_coordinates(glm::vec3 d) {
    const glm::vec3 a = glm::abs(d);
    int face;
    float ma, sc, tc;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x > 0 ? 0 : 1;
        ma = a.x;
        sc = d.x > 0 ? -d.z : d.z;
        tc = -d.y;
    } else if (a.y >= a.z) {
        face = d.y > 0 ? 2 : 3;
        ma = a.y;
        sc = d.x;
        tc = d.y > 0 ? d.z : -d.z;
    } else {
        face = d.z > 0 ? 4 : 5;
        ma = a.z;
        sc = d.z > 0 ? d.x : -d.x;
        tc = -d.y;
    }
    if (!(ma > 0.0f)) {
        return {0, {0.5f, 0.5f}};  // the zero vector (or NaN): any texel, never out of range
    }
    return {face, {0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)}};
}

glm::vec3 cube_direction(int face, glm::vec2 st) {
    const float a = 2.0f * st.x - 1.0f, b = 2.0f * st.y - 1.0f;
    glm::vec3 d;
    switch (face) {
        case 0:
            d = {1.0f, -b, -a};
            break;
        case 1:
            d = {-1.0f, -b, a};
            break;
        case 2:
            d = {a, 1.0f, b};
            break;
        case 3:
            d = {a, -1.0f, -b};
            break;
        case 4:
            d = {a, -b, 1.0f};
            break;
        default:
            d = {-a, -b, -1.0f};
            break;
    }
    return glm::normalize(d);
}

float texel_solid_angle(int size, int x, int y) {
    const double x0 = 2.0 * x / size - 1.0, x1 = 2.0 * (x + 1) / size - 1.0;
    const double y0 = 2.0 * y / size - 1.0, y1 = 2.0 * (y + 1) / size - 1.0;
    return float(face_area(x0, y0) - face_area(x0, y1) - face_area(x1, y0) + face_area(x1, y1));
}

CubeMipChain build_mip_chain(const CubeMap& level0) {
    if (level0.size & (level0.size - 1)) {
        fail("cube map face size {} is not a power of two (needed for its mip chain)", level0.size);
    }
    CubeMipChain chain{level0};
    while (chain.back().size > 1) {
        const CubeMap& fine = chain.back();
        CubeMap coarse(fine.size / 2);
        for (int f = 0; f < 6; ++f)
            for (int y = 0; y < coarse.size; ++y)
                for (int x = 0; x < coarse.size; ++x)
                    coarse.set(
                        f, x, y,
                        0.25f * (fine.texel(f, 2 * x, 2 * y) + fine.texel(f, 2 * x + 1, 2 * y) +
                                 fine.texel(f, 2 * x, 2 * y + 1) +
                                 fine.texel(f, 2 * x + 1, 2 * y + 1)));
        chain.push_back(std::move(coarse));
    }
    return chain;
}

glm::vec3 sample_lod(const CubeMipChain& chain, glm::vec3 d, float lod) {
    const float last = float(chain.size() - 1);
    lod = std::clamp(std::isfinite(lod) ? lod : 0.0f, 0.0f, last);
    const int l0 = int(lod);
    const float t = lod - float(l0);
    const glm::vec3 a = chain[size_t(l0)].sample(d);
    if (t <= 0.0f) {
        return a;
    }
    return a * (1.0f - t) + chain[size_t(l0) + 1].sample(d) * t;
}

glm::vec2 equirect_uv(glm::vec3 d, float rotation_degrees) {
    d = glm::normalize(d);
    float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi) + rotation_degrees / 360.0f;
    u -= std::floor(u);
    return {u, std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi};
}

glm::vec3 equirect_direction(glm::vec2 uv, float rotation_degrees) {
    const float phi = (uv.x - 0.5f - rotation_degrees / 360.0f) * 2.0f * kPi;
    const float theta = uv.y * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

glm::vec3 sample_equirect(const Image& image, glm::vec2 uv) {
    const float px = uv.x * float(image.width) - 0.5f;
    const float py = std::clamp(uv.y * float(image.height) - 0.5f, 0.0f, float(image.height - 1));
    const float x_floor = std::floor(px);
    const float fx = px - x_floor;
    const int x0 = ((int(x_floor) % image.width) + image.width) % image.width;
    const int x1 = (x0 + 1) % image.width;
    const int y0 = int(py), y1 = std::min(y0 + 1, image.height - 1);
    const float fy = py - float(y0);
    const glm::vec3 top = image.at(x0, y0) * (1.0f - fx) + image.at(x1, y0) * fx;
    const glm::vec3 bottom = image.at(x0, y1) * (1.0f - fx) + image.at(x1, y1) * fx;
    return top * (1.0f - fy) + bottom * fy;
}

CubeMap cube_from_equirect(const Image& equirect, int face_size, float rotation_degrees,
                           int supersampling) {
    CubeMap cube(face_size);
    const int n = std::max(1, supersampling);
    tbb::parallel_for(
        tbb::blocked_range<int>(0, 6 * face_size), [&](const tbb::blocked_range<int>& rows) {
            for (int row = rows.begin(); row != rows.end(); ++row) {
                const int f = row / face_size, y = row % face_size;
                for (int x = 0; x < face_size; ++x) {
                    glm::vec3 sum(0.0f);
                    for (int j = 0; j < n; ++j)
                        for (int i = 0; i < n; ++i) {
                            const glm::vec2 st(
                                (float(x) + (float(i) + 0.5f) / float(n)) / float(face_size),
                                (float(y) + (float(j) + 0.5f) / float(n)) / float(face_size));
                            sum += sample_equirect(
                                equirect, equirect_uv(cube_direction(f, st), rotation_degrees));
                        }
                    cube.set(f, x, y, sum / float(n * n));
                }
            }
        });
    return cube;
}

Image faces_to_strip(const CubeMap& cube) {
    Image strip(6 * cube.size, cube.size);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < cube.size; ++y)
            for (int x = 0; x < cube.size; ++x)
                strip.set(f * cube.size + x, y, cube.texel(f, x, y));
    return strip;
}

CubeMap strip_to_faces(const Image& strip) {
    if (strip.width != 6 * strip.height) {
        fail("a cube map strip must be 6n x n texels, not {}x{}", strip.width, strip.height);
    }
    CubeMap cube(strip.height);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < cube.size; ++y)
            for (int x = 0; x < cube.size; ++x)
                cube.set(f, x, y, strip.at(f * cube.size + x, y));
    return cube;
}

}  // namespace sl::ibl
