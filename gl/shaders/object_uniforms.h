// The per-object uniforms of every pass that draws the scene's objects: set by the frame's
// draw_objects() (frame/renderer.h) for its own passes and the translucent G-buffer's
// (sss/shaders/gbuffer.vert), read by their vertex shaders.
#ifndef SL_OBJECT_UNIFORMS_H
#define SL_OBJECT_UNIFORMS_H

#define SL_OBJECT_MODEL 0          // mat4: local -> world
#define SL_OBJECT_NORMAL_MATRIX 1  // mat4: the inverse transpose of model

#endif
