#include "frame/frame_loop.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <future>
#include <memory>
#include <optional>

#include "core/error.h"

namespace sl::frame {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

// The CPU update of one frame, with when it ran.
struct Update {
    std::unique_ptr<FrameWork> work;
    Clock::time_point start, end;
};

Update run_update(const VolumeMethod& method, const Scene& scene, const SceneChange& change) {
    Update u;
    u.start = Clock::now();
    u.work = method.cpu_update(scene, change);
    u.end = Clock::now();
    return u;
}

}  // namespace

const char* to_string(FrameMode mode) {
    return mode == FrameMode::serial ? "serial" : "pipelined";
}

FrameMode parse_frame_mode(const std::string& text) {
    if (text == "serial")
        return FrameMode::serial;
    if (text == "pipelined")
        return FrameMode::pipelined;
    fail("unknown frame mode {} (known: serial, pipelined)", quote(text));
}

double FrameRecord::critical_cpu_ms() const {
    return apply_ms + (update_on_worker ? wait_ms : update_ms);
}

FrameLoop::FrameLoop(SceneRenderer& renderer, VolumeMethod& method, Scene& live, FrameMode mode)
    : renderer_(renderer), method_(method), live_(live), mode_(mode) {}

void FrameLoop::play(int frames, const std::function<Scene(int)>& state,
                     const std::function<void(const FrameRecord&)>& on_frame) {
    const bool pipelined = mode_ == FrameMode::pipelined;
    Scene next;
    SceneChange change;
    Update update;
    std::optional<Update> ready;  // pipelined: this frame's update, done during the last draw
    for (int k = 0; k < frames; ++k) {
        FrameRecord record;
        record.frame = k;
        const Clock::time_point frame_start = Clock::now();
        if (ready) {
            update = std::move(*ready);
            ready.reset();
        } else {
            next = state(k);
            change = scene_change(live_, next);
            update = run_update(method_, next, change);
        }
        record.update_on_worker = pipelined && k > 0;
        record.update_ms = ms_between(update.start, update.end);
        live_ = std::move(next);
        const Clock::time_point apply_start = Clock::now();
        method_.apply_update(live_, change, std::move(update.work));
        record.apply_ms = ms_between(apply_start, Clock::now());

        // Pipelined: the next frame's state and CPU update run on the worker during this draw.
        std::future<Update> pending;  // on a throw, ~future joins the worker
        if (pipelined && k + 1 < frames) {
            next = state(k + 1);
            change = scene_change(live_, next);
            pending = std::async(std::launch::async, [this, scene = next, change] {
                return run_update(method_, scene, change);
            });
        }
        const Clock::time_point draw_start = Clock::now();
        record.gpu = renderer_.draw(method_).gpu;
        const Clock::time_point draw_end = Clock::now();
        record.draw_ms = ms_between(draw_start, draw_end);
        if (pending.valid()) {
            ready = pending.get();  // rethrows the worker's sl::Error
            record.wait_ms = ms_between(draw_end, Clock::now());
            const Clock::time_point a = std::max(ready->start, draw_start);
            const Clock::time_point b = std::min(ready->end, draw_end);
            record.overlap_ms = b > a ? ms_between(a, b) : 0.0;
        }
        record.frame_ms = ms_between(frame_start, Clock::now());
        on_frame(record);
    }
}

}  // namespace sl::frame
