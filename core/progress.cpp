#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace sl {

namespace {
constexpr double kQuietSeconds = 1.0;  // a step quicker than this says nothing
constexpr double kLogSeconds = 10.0;   // how often a non-terminal gets a line
}  // namespace

Progress::Progress(std::string what, size_t total)
    : what_(std::move(what)), total_(total), terminal_(isatty(STDERR_FILENO) != 0) {}

Progress::~Progress() {
    if (shown_) {
        show(done_.load(), true);
    }
}

void Progress::advance() {
    const size_t done = ++done_;
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (elapsed < kQuietSeconds) {
        return;
    }
    const std::lock_guard lock(mutex_);
    const double since = std::chrono::duration<double>(Clock::now() - shown_at_).count();
    if (!shown_ || terminal_ || since >= kLogSeconds) {
        show(done, false);
    }
}

void Progress::show(size_t done, bool last) {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    if (last) {
        std::fprintf(stderr, "%s%s: %zu of %zu done in %.1f s\n", terminal_ ? "\r" : "",
                     what_.c_str(), done, total_, elapsed);
    } else {
        std::fprintf(stderr, "%s%s: %zu of %zu (%.0f s)%s", terminal_ ? "\r" : "", what_.c_str(),
                     done, total_, elapsed, terminal_ ? "" : "\n");
    }
    std::fflush(stderr);
    shown_ = true;
    shown_at_ = Clock::now();
}

}  // namespace sl
