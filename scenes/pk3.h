#pragma once
// Quake 3 pk3 archives (zip files, as id Tech 3 and OpenArena ship their maps, textures and
// models): one entry read into memory, through minizip. A scene names a map inside one as
// `[[models]] file = "…/pak1-maps.pk3"`, `map = "maps/dm6ish.bsp"` (docs/scenes.md).

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace sl::pk3 {

// The largest entry read (a game level's .bsp is a few megabytes).
constexpr size_t kMaxEntryBytes = size_t(256) << 20;

// The bytes of `entry` (a path inside the archive, matched without regard to case, as the game
// does). Throws sl::Error naming the archive: when it is not a zip file, when the entry is missing
// (with the nearest names it holds), larger than kMaxEntryBytes, or cannot be inflated.
std::vector<std::byte> read_entry(const std::filesystem::path& archive, const std::string& entry);

// The names of the archive's entries of one extension, given in lower case (".bsp": its maps;
// any case in the archive), in archive order.
std::vector<std::string> entries(const std::filesystem::path& archive,
                                 const std::string& extension);

}  // namespace sl::pk3
