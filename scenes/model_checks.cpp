#include "scenes/model_checks.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/text.h"
#include "scenes/mesh.h"

namespace sl {

namespace fs = std::filesystem;

void check_obj_indices(const fs::path& path) {
    // Two passes: the counts, then the indices.
    enum Kind { kPosition, kTexture, kNormal };
    static constexpr const char* keywords[3] = {"v", "vt", "vn"};
    static constexpr const char* names[3] = {"vertex", "texture coordinate", "normal"};
    // Calls visit(line number, keyword, rest of the line) for each logical line ('\\' continues).
    auto for_each_line = [&](auto&& visit) {
        std::ifstream in(path, std::ios::binary);
        if (!in) {
            fail("{}: cannot open model file", path.string());
        }
        std::string text, line;
        int number = 0, first = 0;
        while (std::getline(in, text)) {
            ++number;
            first = line.empty() ? number : first;
            const bool continued = !text.empty() && text.back() == '\\';
            line.append(text, 0, text.size() - (continued ? 1 : 0));
            if (continued) {
                line += ' ';
                continue;
            }
            std::string_view rest(line);
            rest.remove_prefix(std::min(rest.size(), rest.find_first_not_of(" \t")));
            const std::string_view keyword = rest.substr(0, rest.find_first_of(" \t\r"));
            visit(first, keyword, rest.substr(keyword.size()));
            line.clear();
        }
    };
    auto kind_of = [](std::string_view keyword) {
        for (int kind = kPosition; kind <= kNormal; ++kind) {
            if (keyword == keywords[kind]) {
                return kind;
            }
        }
        return -1;
    };
    long long totals[3] = {0, 0, 0};
    for_each_line([&](int, std::string_view keyword, std::string_view) {
        if (const int kind = kind_of(keyword); kind >= 0) {
            ++totals[kind];
        }
    });
    long long so_far[3] = {0, 0, 0};
    for_each_line([&](int number, std::string_view keyword, std::string_view rest) {
        if (const int kind = kind_of(keyword); kind >= 0) {
            ++so_far[kind];
            return;
        }
        if (keyword != "f" && keyword != "l" && keyword != "p") {
            return;
        }
        auto check = [&](int kind, std::string_view token) {
            long long index = 0;
            const auto [end, error] =
                std::from_chars(token.data(), token.data() + token.size(), index);
            if (error != std::errc() || end == token.data()) {
                return;  // not an integer (or an empty v//vn slot): assimp's parser decides
            }
            if (index == 0 || (index > 0 ? index > totals[kind] : -index > so_far[kind])) {
                fail("{}:{}: {} index {} out of range (the file has {} '{}' lines{})",
                     path.string(), number, names[kind], index, totals[kind], keywords[kind],
                     index < 0 ? fmt::format(", {} before this one", so_far[kind]) : "");
            }
        };
        for (size_t start = rest.find_first_not_of(" \t\r"); start != std::string_view::npos;) {
            const size_t end = std::min(rest.size(), rest.find_first_of(" \t\r", start));
            std::string_view corner = rest.substr(start, end - start);  // v, v/vt, v//vn, v/vt/vn
            for (int kind = kPosition; kind <= kNormal && !corner.empty(); ++kind) {
                const size_t slash = corner.find('/');
                check(kind, corner.substr(0, slash));
                corner =
                    slash == std::string_view::npos ? std::string_view() : corner.substr(slash + 1);
            }
            start = rest.find_first_not_of(" \t\r", end);
        }
    });
}

namespace {

// The bytes of a PLY scalar type, or 0 for a name that is not one.
int ply_type_size(std::string_view type) {
    static constexpr std::array<std::pair<std::string_view, int>, 16> kTypes = {{
        {"char", 1},
        {"int8", 1},
        {"uchar", 1},
        {"uint8", 1},
        {"short", 2},
        {"int16", 2},
        {"ushort", 2},
        {"uint16", 2},
        {"int", 4},
        {"int32", 4},
        {"uint", 4},
        {"uint32", 4},
        {"float", 4},
        {"float32", 4},
        {"double", 8},
        {"float64", 8},
    }};
    for (const auto& [name, size] : kTypes) {
        if (name == type) {
            return size;
        }
    }
    return 0;
}

// Fails naming the header line and the reason.
using PlyError = std::function<void(int line, const std::string& reason)>;

struct PlyProperty {
    int size = 0;        // a scalar's bytes, or a list's items' bytes
    int count_size = 0;  // a list's count's bytes; 0 for a scalar
};

struct PlyElement {
    std::string name;
    long long count = 0;
    int line = 0;
    std::vector<PlyProperty> properties;
    long long min_tokens = 0;  // per item in ASCII: one per scalar property and list count
};

// A PLY header: its format and elements, read up to end_header.
struct PlyHeader {
    std::string format;
    std::vector<PlyElement> elements;
    int lines = 0;  // the header's lines
};

// Walks the binary data item by item (each list's count read, its items skipped): the element
// and item where the data ends, if it ends before the header's counts are met.
void check_ply_binary_data(std::ifstream& in, const PlyHeader& header, const PlyError& error) {
    const bool big_endian = header.format == "binary_big_endian";
    for (const PlyElement& element : header.elements) {
        for (long long item = 0; item < element.count; ++item) {
            for (const PlyProperty& property : element.properties) {
                long long bytes = property.size;
                if (property.count_size > 0) {
                    unsigned char raw[4] = {0, 0, 0, 0};
                    if (!in.read(reinterpret_cast<char*>(raw), property.count_size)) {
                        bytes = -1;
                    } else {
                        unsigned long long count = 0;
                        for (int k = 0; k < property.count_size; ++k) {
                            const int at = big_endian ? k : property.count_size - 1 - k;
                            count = count << 8 | raw[at];
                        }
                        bytes = static_cast<long long>(count) * property.size;
                    }
                }
                if (bytes < 0 || !in.ignore(bytes) || in.gcount() != bytes) {
                    error(header.lines,
                          fmt::format("the data ends in element {} item {} of {} (line {}): "
                                      "the file is truncated, or its header's counts or types are "
                                      "wrong",
                                      quote(element.name), item + 1, element.count, element.line));
                }
            }
        }
    }
}

constexpr std::string_view kPlyTypes =
    "char, uchar, short, ushort, int, uint, float, double or their sized names";

// An `element NAME COUNT` line, its count held to the mesh limits.
PlyElement ply_element(std::istringstream& words, int line, const PlyError& error) {
    PlyElement element;
    std::string count;
    words >> element.name >> count;
    const auto [end, code] =
        std::from_chars(count.data(), count.data() + count.size(), element.count);
    if (code != std::errc() || end != count.data() + count.size() || element.count < 0) {
        error(line, fmt::format("element {}: count {} is not a non-negative integer",
                                quote(element.name), quote(count)));
    }
    const long long limit = element.name == "face" ? kMaxMeshTriangles : kMaxMeshVertices;
    if (element.count > limit) {
        error(line, fmt::format("element {} declares {} items, at most {} (scenes/mesh.h)",
                                quote(element.name), element.count, limit));
    }
    element.line = line;
    return element;
}

// A `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME` line.
PlyProperty ply_property(std::istringstream& words, int line, const PlyError& error) {
    std::string type;
    words >> type;
    if (type != "list") {
        if (ply_type_size(type) == 0) {
            error(line,
                  fmt::format("unknown property type {} (expected {})", quote(type), kPlyTypes));
        }
        return {ply_type_size(type), 0};
    }
    std::string count_type, item_type;
    words >> count_type >> item_type;
    for (const std::string& t : {count_type, item_type}) {
        if (ply_type_size(t) == 0) {
            error(line, fmt::format("unknown list type {} (expected {})", quote(t), kPlyTypes));
        }
    }
    if (count_type == "float" || count_type == "float32" || count_type == "double" ||
        count_type == "float64") {
        error(line,
              fmt::format("a list's count must be an integer type, not {}", quote(count_type)));
    }
    return {ply_type_size(item_type), ply_type_size(count_type)};
}

// The header is text up to end_header; a real one is a few dozen lines.
PlyHeader read_ply_header(std::ifstream& in, const PlyError& error) {
    PlyHeader header;
    std::string text;
    int& line = header.lines;
    bool ended = false;
    while (!ended && line < 10000 && std::getline(in, text)) {
        ++line;
        if (!text.empty() && text.back() == '\r') {
            text.pop_back();
        }
        std::istringstream words(text);
        std::string keyword;
        words >> keyword;
        if (line == 1) {
            if (keyword != "ply") {
                error(line, "not a PLY file (the first line is not 'ply')");
            }
        } else if (keyword == "format") {
            words >> header.format;
            if (header.format != "ascii" && header.format != "binary_little_endian" &&
                header.format != "binary_big_endian") {
                error(line, fmt::format("unknown format {} (expected ascii, binary_little_endian "
                                        "or binary_big_endian)",
                                        quote(header.format)));
            }
        } else if (keyword == "element") {
            header.elements.push_back(ply_element(words, line, error));
        } else if (keyword == "property") {
            if (header.elements.empty()) {
                error(line, "a property before any element");
            }
            header.elements.back().properties.push_back(ply_property(words, line, error));
            ++header.elements.back().min_tokens;
        } else if (keyword == "end_header") {
            ended = true;
        } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
            error(line, fmt::format("unknown header line {}", quote(keyword)));
        }
    }
    if (!ended) {
        error(line, "no end_header line");
    }
    if (header.format.empty()) {
        error(line, "the header has no format line");
    }
    return header;
}

// ASCII data: at least one number per scalar property and list count of every item.
void check_ply_ascii_data(std::ifstream& in, const PlyHeader& header, const PlyError& error) {
    long long tokens_needed = 0;
    std::string declared;
    for (const PlyElement& element : header.elements) {
        tokens_needed += element.count * element.min_tokens;
        declared += fmt::format("{}{} {} (line {})", declared.empty() ? "" : ", ", element.count,
                                element.name, element.line);
    }
    long long tokens = 0;
    std::string token;
    while (tokens < tokens_needed && in >> token) {
        ++tokens;
    }
    if (tokens < tokens_needed) {
        error(header.lines,
              fmt::format("the header declares {}, which need at least {} numbers, but "
                          "{} follow end_header: the file is truncated or its counts "
                          "are wrong",
                          declared, tokens_needed, tokens));
    }
}

}  // namespace

void check_ply_header(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        fail("{}: cannot open model file", path.string());
    }
    const PlyError error = [&](int line, const std::string& reason) {
        fail("{}:{}: {}", path.string(), line, reason);
    };
    const PlyHeader header = read_ply_header(in, error);
    if (header.format == "ascii") {
        check_ply_ascii_data(in, header, error);
    } else {
        check_ply_binary_data(in, header, error);
    }
}

}  // namespace sl
