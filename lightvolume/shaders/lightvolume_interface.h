// The interface of the light volume's grid (grid.glsl), shared by lightvolume/light_volume.cpp
// and the shaders (uniform locations, the light-depth texture unit).
#ifndef SL_LIGHTVOLUME_INTERFACE_H
#define SL_LIGHTVOLUME_INTERFACE_H

#define SL_LIGHT_VOLUME_RESOLUTION 10  // N, vertices per side
#define SL_LIGHT_VOLUME_CLIP_TO_WORLD 11
#define SL_LIGHT_VOLUME_LIGHT_DEPTH_UNIT 1  // the shadow map, read plainly

#endif
