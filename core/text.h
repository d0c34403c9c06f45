#pragma once
// User bytes in messages: whatever a file or the command line holds (binary headers, control
// bytes, megabytes of one token) is shown as one printable line. printable() escapes what a
// terminal would act on or cannot show; quote() also truncates and puts the result in quotes,
// for a value echoed inside an error message.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

namespace sl {

// `text` with control bytes (and DEL) as \n, \r, \t or \xNN and bytes that are not valid UTF-8
// as \xNN; valid UTF-8 (σ, ², …) is kept.
std::string printable(std::string_view text);

// printable(text), cut after `max_bytes` of input with "…" and the full size: for a name echoed
// as it is (a TOML key).
std::string clipped(std::string_view text, size_t max_bytes = 64);
// The same in single quotes: for a value echoed inside a message ("unknown shape 'sphre'").
std::string quote(std::string_view text, size_t max_bytes = 64);

// The file's extension in ASCII lower case (".bsp" for "DM6.BSP"): how a loader is picked.
std::string lower_extension(const std::filesystem::path& path);

// The whole of a text file (scene files, animation paths). Throws sl::Error "PATH: cannot read
// WHAT", with "(no such file)" when it is not a regular file.
std::string read_text_file(const std::filesystem::path& path, std::string_view what);

}  // namespace sl
