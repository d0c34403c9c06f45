#pragma once
// Playing a moving scene (docs/design.md §10): every frame brings the method to the frame's scene
// (VolumeMethod::cpu_update then apply_update) and draws it. Two modes:
//   serial     frame k: CPU update for scene k, then its draw; the CPU and the GPU take turns.
//   pipelined  while the GPU draws frame k, a worker thread runs the CPU update for frame k+1
//              (the beam tree, its regions and meshes: the "hybrid CPU/GPU" of the project's
//              name); the GL thread then only installs it (apply_update: uploads) before drawing.
// The states of an animation are known in advance, so the pipelined frames show exactly the
// serial ones (tested). An interactive caller (the viewer) hands in the scene of frame k+1 when
// frame k starts: what it shows lags its input by one frame, the pipeline's one frame of
// latency.

#include <functional>
#include <vector>

#include "frame/renderer.h"
#include "frame/volume_method.h"
#include "scenes/animation.h"

namespace sl::frame {

enum class FrameMode { serial, pipelined };
const char* to_string(FrameMode mode);
FrameMode parse_frame_mode(const std::string& text);  // throws sl::Error naming the choices

// One frame's costs, milliseconds of wall time.
struct FrameRecord {
    int frame = 0;
    double update_ms = 0.0;   // cpu_update for this frame (on the worker when pipelined)
    double apply_ms = 0.0;    // apply_update, on the GL thread
    double wait_ms = 0.0;     // pipelined: the GL thread waiting for the worker after the draw
    double draw_ms = 0.0;     // SceneRenderer::draw: submitting the passes and waiting for them
    double frame_ms = 0.0;    // the GL thread's whole frame, the callback excluded
    double overlap_ms = 0.0;  // pipelined: the next frame's cpu_update that ran during this draw
    bool update_on_worker = false;  // this frame's cpu_update ran on the worker (pipelined, k > 0)
    PassTimings gpu;                // GPU time per pass
    // The CPU work the frame waited for on the GL thread: serial, update + apply; pipelined,
    // apply + the wait for the worker (what the worker did during the draw is hidden).
    double critical_cpu_ms() const;
};

class FrameLoop {
public:
    // `live` is the scene `renderer` was made for (it draws whatever `live` holds); it must be
    // the scene `method` was last prepared or updated for.
    FrameLoop(SceneRenderer& renderer, VolumeMethod& method, Scene& live, FrameMode mode);

    // Draws `frames` frames: frame k shows state(k) (called once per frame, in order; when
    // pipelined, state(k+1) is called just before frame k draws). After each draw, on_frame(record)
    // runs on the GL thread with the frame's images still in the renderer (read them back
    // there). An exception from state(), an update or on_frame() stops the loop after the
    // worker is joined, and propagates.
    void play(int frames, const std::function<Scene(int)>& state,
              const std::function<void(const FrameRecord&)>& on_frame);

private:
    SceneRenderer& renderer_;
    VolumeMethod& method_;
    Scene& live_;
    FrameMode mode_;
};

}  // namespace sl::frame
