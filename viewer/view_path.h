#pragma once
// A camera and light path for the viewer's scripted mode (`shaftlab view --path FILE`), TOML:
//
//   [[key]]
//   frame = 0                       (keys in increasing frame order)
//   camera_position = [x, y, z]     camera_target = [x, y, z]
//   light_position = [x, y, z]      light_target = [x, y, z]
//   cone_angle = 25.0               (degrees)
//
// Each quantity is its own track: linear between the keys that set it, held before the first
// and after the last; a quantity no key sets is left as the scene has it.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scenes/scene.h"

namespace sl::viewer {

class ViewPath {
public:
    // Throws sl::Error naming the file, line and key on bad input.
    static ViewPath load(const std::filesystem::path& path);
    static ViewPath parse(const std::string& text, const std::string& origin);

    // Sets the scene's camera and light to the path at `frame`.
    void apply(int frame, Scene& scene) const;
    int last_frame() const { return last_frame_; }

private:
    template <typename T>
    struct Track {
        std::vector<std::pair<int, T>> keys;
        std::optional<T> at(int frame) const;
    };
    Track<glm::vec3> camera_position_, camera_target_, light_position_, light_target_;
    Track<float> cone_angle_;
    int last_frame_ = 0;
};

}  // namespace sl::viewer
