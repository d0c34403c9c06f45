#include "core/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>

#include "core/error.h"

namespace sl {

namespace {

// Length of the valid UTF-8 sequence starting at text[i] (1 to 4), or 0 when it is not one.
size_t utf8_sequence(std::string_view text, size_t i) {
    const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
    const unsigned char lead = byte(i);
    size_t length = 0;
    unsigned min = 0;
    if (lead >= 0xc2 && lead <= 0xdf) {
        length = 2, min = 0x80;
    } else if (lead >= 0xe0 && lead <= 0xef) {
        length = 3, min = 0x800;
    } else if (lead >= 0xf0 && lead <= 0xf4) {
        length = 4, min = 0x10000;
    } else {
        return 0;
    }
    if (i + length > text.size()) {
        return 0;
    }
    unsigned code = lead & (0xff >> (length + 1));
    for (size_t k = 1; k < length; ++k) {
        if ((byte(i + k) & 0xc0) != 0x80) {
            return 0;
        }
        code = code << 6 | (byte(i + k) & 0x3f);
    }
    const bool surrogate = code >= 0xd800 && code <= 0xdfff;
    return code >= min && code <= 0x10ffff && !surrogate ? length : 0;
}

}  // namespace

std::string printable(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += char(c);
            ++i;
        } else if (c == '\n') {
            out += "\\n", ++i;
        } else if (c == '\r') {
            out += "\\r", ++i;
        } else if (c == '\t') {
            out += "\\t", ++i;
        } else if (const size_t length = c >= 0x80 ? utf8_sequence(text, i) : 0; length > 0) {
            out.append(text.substr(i, length));
            i += length;
        } else {
            out += fmt::format("\\x{:02x}", c);
            ++i;
        }
    }
    return out;
}

namespace {

// The prefix of `text` of at most `max_bytes`, not cutting a UTF-8 sequence.
std::string_view cut(std::string_view text, size_t max_bytes) {
    size_t n = max_bytes;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xc0) == 0x80) {
        --n;
    }
    return text.substr(0, n);
}

}  // namespace

std::string clipped(std::string_view text, size_t max_bytes) {
    if (text.size() <= max_bytes) {
        return printable(text);
    }
    return fmt::format("{}… ({} bytes)", printable(cut(text, max_bytes)), text.size());
}

std::string quote(std::string_view text, size_t max_bytes) {
    if (text.size() <= max_bytes) {
        return fmt::format("'{}'", printable(text));
    }
    return fmt::format("'{}…' ({} bytes)", printable(cut(text, max_bytes)), text.size());
}

std::string lower_extension(const std::filesystem::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

std::string read_text_file(const std::filesystem::path& path, std::string_view what) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        const char* why = std::filesystem::is_directory(path, ec) ? "it is a directory"
                          : std::filesystem::exists(path, ec)     ? "not a regular file"
                                                                  : "no such file";
        fail("{}: cannot read {} ({})", path.string(), what, why);
    }
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (!in && !in.eof()) {
        fail("{}: cannot read {}", path.string(), what);
    }
    return text;
}

}  // namespace sl
