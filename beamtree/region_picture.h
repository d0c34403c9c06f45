#pragma once
// The regions seen from the camera (Nilsson figure 5.4's colours): every pixel's eye ray, from
// the near plane up to the first surface, composited front to back through the influence volume
// with lit yellow, uncertain grey and unlit black, over a picture of the scene. `shaftlab regions`
// writes it as regions.png.

#include <cstdint>
#include <span>
#include <vector>

#include "beamtree/beam_tree.h"
#include "scenes/scene.h"

namespace sl::bt {

// `depth` is the scene camera's window-space depth in [0, 1] and `srgb8` its picture (RGB), both
// width x height, rows top to bottom. Rays are traced through the tree (BeamTree::trace) at every
// other pixel in x and y; a pixel between traced ones whose neighbours cross the same sequence of
// regions and reach nearly the same depth takes the mean of their interval ends (they are smooth
// in the pixel there; the difference is below the 8-bit output), any other pixel is traced
// itself. Throws sl::Error when the buffers do not have the picture's size.
std::vector<uint8_t> draw_regions(const Scene& scene, const BeamTree& tree,
                                  std::span<const float> depth, std::span<const uint8_t> srgb8,
                                  int width, int height);

}  // namespace sl::bt
