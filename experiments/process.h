#pragma once
// Child processes of the harness: a cell in a process of its own (process isolation) and the
// plotting script.

#include <string>
#include <vector>

namespace sl::experiments {

// Runs a program and waits for it; returns its exit status (128 + signal when killed). Throws
// sl::Error when it cannot be started.
int spawn_and_wait(const std::vector<std::string>& arguments);

}  // namespace sl::experiments
