#pragma once
// Cube maps on the CPU: OpenGL's face layout and texel addressing (so a face uploads as it is),
// bilinear and trilinear lookups, exact texel solid angles, box-filtered mip chains, and the
// conversion from equirectangular (latitude-longitude) images.
//
// Faces are in GL order +X, -X, +Y, -Y, +Z, -Z; within a face, row 0 is GL's t = 0 and column 0
// its s = 0 (OpenGL 4.5 core, table 8.19: major axis ma, s = (sc/|ma| + 1)/2, t = (tc/|ma| + 1)/2).
// World directions are y-up, the scene's convention.

#include <array>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/image.h"

namespace sl::ibl {

struct CubeMap {
    int size = 0;                // face width = height in texels
    std::array<Image, 6> faces;  // GL order, RGB linear radiance

    CubeMap() = default;
    explicit CubeMap(int face_size);

    glm::vec3 texel(int face, int x, int y) const { return faces[size_t(face)].at(x, y); }
    void set(int face, int x, int y, glm::vec3 value) { faces[size_t(face)].set(x, y, value); }
    // Unit direction through the centre of texel (x, y) of `face`.
    glm::vec3 direction(int face, int x, int y) const;
    // Bilinear lookup in direction d (need not be unit), seamless across face edges.
    glm::vec3 sample(glm::vec3 d) const;
};

// Level 0 is the source; each next level halves the face size (down to 1 texel).
using CubeMipChain = std::vector<CubeMap>;

// The face and the face coordinates in [0, 1]² that direction d falls on.
struct CubeCoordinates {
    int face;
    glm::vec2 st;
};
CubeCoordinates cube_coordinates(glm::vec3 d);
// The unit direction through face coordinates st in [0, 1]² of `face` (cube_coordinates' inverse).
glm::vec3 cube_direction(int face, glm::vec2 st);
// Exact solid angle of texel (x, y) on a face of `size` texels (the same on every face).
float texel_solid_angle(int size, int x, int y);

// Box-filtered chain down to 1x1 texel per face (the source mips of filtered importance sampling).
CubeMipChain build_mip_chain(const CubeMap& level0);
// Trilinear lookup: bilinear in the two levels around `lod`, clamped to the chain.
glm::vec3 sample_lod(const CubeMipChain& chain, glm::vec3 d, float lod);

// Equirectangular convention (y up): u = 1/2 + atan2(d.x, -d.z)/(2π), v = acos(d.y)/π, v = 0 the
// top row (the zenith). `rotation_degrees` turns the environment about +y.
glm::vec2 equirect_uv(glm::vec3 d, float rotation_degrees = 0.0f);
glm::vec3 equirect_direction(glm::vec2 uv, float rotation_degrees = 0.0f);
// Bilinear, wrapping in u and clamping in v.
glm::vec3 sample_equirect(const Image& image, glm::vec2 uv);
// Resamples with `supersampling`² bilinear taps per cube texel.
CubeMap cube_from_equirect(const Image& equirect, int face_size, float rotation_degrees = 0.0f,
                           int supersampling = 2);

// A cube map filled from a function of the texel-centre direction (tests, analytic sources).
template <typename F>
CubeMap make_cube_map(int face_size, F&& radiance) {
    CubeMap cube(face_size);
    for (int f = 0; f < 6; ++f)
        for (int y = 0; y < face_size; ++y)
            for (int x = 0; x < face_size; ++x)
                cube.set(f, x, y, radiance(cube.direction(f, x, y)));
    return cube;
}

// The six faces side by side (+X … -Z, left to right) as one 6n x n image; and back.
Image faces_to_strip(const CubeMap& cube);
CubeMap strip_to_faces(const Image& strip);

}  // namespace sl::ibl
