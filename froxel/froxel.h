#pragma once
// `froxel`: frustum-aligned voxel fog as engines ship it (Wronski 2014, "Volumetric fog",
// Assassin's Creed IV; Hillaire 2015, "Physically based and unified volumetric rendering in
// Frostbite"; the same design in Unity HDRP, Unreal and Godot 4). Three compute passes and a
// full-screen one:
//   inject     each froxel's in-scattering density from the shared light model with shadow-map
//              visibility, `samples` points stratified along its depth span, optionally jittered
//              per frame (shaders/inject.comp);
//   temporal   optional: reprojection into the last frame's grid and an exponential history,
//              clamped to the current neighbourhood (shaders/temporal.comp);
//   integrate  front to back along each column with Hillaire's energy-conserving step
//              (shaders/integrate.comp);
//   apply      each pixel reads the integral at its surface's view depth (shaders/apply.frag).
// The grid: 160 x 90 columns at 1280 x 720, scaled with the image and by grid_scale, and
// grid_scale x slices slices from the eye to depth_extent, exponential in depth with a linear part
// near the eye (shaders/grid.glsl). Its error is the grid's: in depth from the slices, across
// from the columns (a shaft's edge is blurred over a froxel), in visibility from one shadow lookup
// per sample.
// Parameters: grid_scale, slices, depth_extent, linear_depth, samples, jitter, temporal, history,
// shadow, shadow_size. Statistics: the grid's size and froxels, its depth extent.

#include <memory>

#include <glm/vec3.hpp>

#include "frame/volume_method.h"
#include "gl/objects.h"

namespace sl::frame {
class MethodRegistry;
}

namespace sl::froxel {

// The grid of one frame: columns x rows x slices, and the slicing's depth extent E and linear
// part c (shaders/grid.glsl): slice boundary s lies at view depth c ((E + c) / c)^(s / D) - c.
struct FroxelGrid {
    glm::ivec3 size{1, 1, 1};
    float depth_extent = 1.0f;
    float linear_depth = 1.0f;
    bool operator==(const FroxelGrid&) const = default;
};

// The view depth of slice boundary s (0 at the eye, size.z at depth_extent): grid.glsl's
// slice_depth in double precision.
double slice_depth(const FroxelGrid& grid, double s);

// The farthest view depth of the light's influence pyramid (a sun's: its box as the frame's shadow
// map is fitted to the camera at `aspect`, frame/shadow_fit.h) from the scene's camera, within the
// camera's far plane (its near plane when the light is wholly behind the eye): what an automatic
// depth_extent covers, so that no lit froxel is left out.
double influence_depth(const Scene& scene, double aspect);

// The grid for an image of width x height: round(160 x grid_scale x width / 1280) x
// round(90 x grid_scale x height / 720) x round(slices x grid_scale), each at least 1;
// depth_extent 0 is influence_depth(scene, width / height), linear_depth 0 is an eighth of the
// extent. Throws sl::Error when a side exceeds 2048 (the 3D texture size every GL 4.5 offers) or
// the grid 2^26 froxels.
FroxelGrid make_grid(const Scene& scene, int width, int height, double grid_scale, int slices,
                     double depth_extent, double linear_depth);

// The integration pass on its own (the method's, and the energy test's): reads `densities`
// (RGBA32F 3D, the grid's size) and writes the integral to each slice's far side into
// `integrated`. Needs the frame's uniform block bound.
class FroxelIntegrator {
public:
    void integrate(const FroxelGrid& grid, GLuint densities, GLuint integrated) const;

private:
    mutable gl::Program program_;
};

// Registers `froxel` (frame/method_registry.h).
void register_methods(frame::MethodRegistry& registry);

}  // namespace sl::froxel
