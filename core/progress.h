#pragma once
// Progress of a CPU step that can take seconds (the convex pieces of a large model, a
// reference): silent when the step is quick; after a second, one line on stderr saying what it is
// and how far it has got, rewritten in place on a terminal and repeated every ten seconds
// otherwise (a log keeps a trace), and a last line with the time it took. Thread-safe: advance()
// may be called from the workers of a parallel loop.

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace sl {

class Progress {
public:
    // `what` names the step ("bounding volumes of 12 meshes"); `total` counts its units.
    Progress(std::string what, size_t total);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // One more unit done.
    void advance();

private:
    using Clock = std::chrono::steady_clock;
    void show(size_t done, bool last);

    std::string what_;
    size_t total_;
    std::atomic<size_t> done_{0};
    Clock::time_point start_ = Clock::now();
    Clock::time_point shown_at_{};
    bool shown_ = false;
    bool terminal_ = false;
    std::mutex mutex_;
};

}  // namespace sl
