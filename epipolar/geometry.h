#pragma once
// The epipolar geometry of a frame (Engelhardt & Dachsbacher 2010, §3; Yusov 2013/2014, "slices"),
// on the CPU in double precision: what the epipolar method uploads each frame, and the twin of
// the GLSL unwarp (shaders/epipolar.glsl) the tests compare against.
//
// Every eye ray whose pixel lies on a line through the light's screen position P lies in one
// plane with the camera and the light (an epipolar plane). The image is cut into `slices` such
// lines, from P (or from where the line enters the image, when P is outside) to an exit point on
// the image border. The exit points are spread evenly along the part of the border that can be an
// exit: the whole border when P is inside the image, the sides that do not face P otherwise.
// Seen from the light, an epipolar plane is one line of the shadow map (Chen et al. 2011, §4):
// every eye ray of the slice projects onto it, so one 1D min-max tree of the depths along that
// line serves every ray of the slice.
//
// Coordinates: window pixels as gl_FragCoord (0 at the image's lower left corner, pixel centres
// at + 0.5); the shadow map in [0, 1]² (its texture coordinates).

#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace sl::epipolar {

// The frame's cameras as the geometry needs them.
struct Views {
    glm::dmat4 view_projection;        // camera: world -> clip
    glm::dmat4 light_view_projection;  // shadow map: world -> light clip
    glm::dvec3 camera;                 // camera position
    // The light as a homogeneous point: (position, 1), or for a directional light (the sun) the
    // point at infinity it shines from, (-direction, 0) (Yusov 2013/2014: the sun's epipolar
    // lines meet at its projection, or run parallel when it lies in the camera's plane).
    glm::dvec4 light{0.0, 0.0, 0.0, 1.0};
    int width = 1, height = 1;  // image size in pixels
};

// The part of the image border where slices end, walked counter-clockwise from `start`
// (a perimeter position: 0 at the lower left corner, along the bottom, right, top and left
// sides, 2 (width + height) in all), `length` long; `periodic` when it is the whole border.
struct ExitArc {
    double start = 0.0, length = 0.0;
    bool periodic = true;
};

// The light's screen position: its projection in window pixels, also when it lies behind the
// camera (the epipolar lines meet at the projection of the point opposite it; they are the same
// lines). A sun projects like any point at infinity: to where its direction is seen (Yusov's
// sun on screen or off it), or to the anti-solar point when it is behind the camera. A light in
// the camera's plane (for a sun: a direction perpendicular to the view) projects to infinity: the
// position is moved to 1e3 image diagonals from the centre, in its direction, where the lines are
// parallel to a few 1e-4 px.
glm::dvec2 light_screen_position(const Views& views);

// Whether P lies inside the image (then every slice starts at P).
bool inside_image(glm::dvec2 p, int width, int height);

ExitArc exit_arc(glm::dvec2 p, int width, int height);

// The point of the border at perimeter position `s` (taken modulo the perimeter), and back.
glm::dvec2 border_point(double s, int width, int height);
double perimeter_position(glm::dvec2 border, int width, int height);

// Where the ray from p through x leaves the image: the largest λ with p + λ (x - p) in it.
glm::dvec2 exit_point(glm::dvec2 p, glm::dvec2 x, int width, int height);

// One slice: its segment in the image, from `entry` to `exit` (equal when the slice crosses
// no pixel), and its line in the shadow map, `map_origin` + u `map_step` for u in [0, texels),
// the part of the line inside [0, 1]² (map_step 0 when the line misses the map).
struct Slice {
    glm::dvec2 entry{0.0}, exit{0.0};
    glm::dvec2 map_origin{0.0}, map_step{0.0};
};

// Slice s ends at the arc's point (s + 1/2) / slices of the way along it.
std::vector<Slice> make_slices(const Views& views, int slices, int map_texels);

// The fractional slice coordinate of pixel position x: c such that the slice through x lies
// between slices floor(c) and floor(c) + 1 (taken modulo `slices` when the arc is periodic); the
// GLSL twin is shaders/epipolar.glsl's slice_coordinate.
double slice_coordinate(glm::dvec2 p, const ExitArc& arc, glm::dvec2 x, int slices, int width,
                        int height);

// The rectified map's texels per slice for a shadow map of `map_size` texels per side: the
// power of two at or above map_size (Chen et al. 2011 §4: the map's resolution; a diagonal line
// steps √2 map texels), at least 64 (a work group of rectify.comp) and at most 8192 (the tree's
// levels take two of them in one texture row, 16384 texels, GL 4.5's least maximum).
int map_texels(int map_size);

}  // namespace sl::epipolar
