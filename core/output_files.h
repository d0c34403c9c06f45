#pragma once
// All-or-nothing output: every file of a result is written under a temporary name and renamed into
// place only when all of them were written, so a failure never leaves a half-written result; the
// folders made for it are removed again when nothing was committed into them.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace sl {

class OutputFiles {
public:
    explicit OutputFiles(std::filesystem::path directory);
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;
    // Removes the temporaries of an uncommitted set, and the folders the constructor made.
    ~OutputFiles();

    // Calls write(temporary path); the file appears as directory/name on commit().
    void add(const std::string& name,
             const std::function<void(const std::filesystem::path&)>& write);
    void add_text(const std::string& name, const std::string& text);
    // Renames every temporary into place. Returns the final paths.
    std::vector<std::filesystem::path> commit();

private:
    std::filesystem::path directory_;
    std::vector<std::filesystem::path> created_;  // the folders made, deepest last
    bool committed_ = false;
    std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temp, final
};

}  // namespace sl
