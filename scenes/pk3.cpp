#include "scenes/pk3.h"

#include <algorithm>
#include <cctype>
#include <memory>

#include <unzip.h>

#include "core/error.h"
#include "core/suggest.h"
#include "core/text.h"

namespace sl::pk3 {

namespace fs = std::filesystem;

namespace {

// The open archive, closed on every path out.
struct Archive {
    unzFile file = nullptr;
    explicit Archive(const fs::path& path) : file(unzOpen64(path.c_str())) {
        if (!file) {
            fail("{}: cannot open the pk3 (not a zip archive, or unreadable)", path.string());
        }
    }
    ~Archive() { unzClose(file); }
    Archive(const Archive&) = delete;
    Archive& operator=(const Archive&) = delete;
};

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// Every entry's name and uncompressed size, in archive order.
std::vector<std::pair<std::string, uint64_t>> listing(const Archive& archive,
                                                      const fs::path& path) {
    std::vector<std::pair<std::string, uint64_t>> result;
    for (int status = unzGoToFirstFile(archive.file); status == UNZ_OK;
         status = unzGoToNextFile(archive.file)) {
        unz_file_info64 info;
        char name[1024];
        if (unzGetCurrentFileInfo64(archive.file, &info, name, sizeof name, nullptr, 0, nullptr,
                                    0) != UNZ_OK) {
            fail("{}: cannot read the archive's directory", path.string());
        }
        result.emplace_back(std::string(name), info.uncompressed_size);
    }
    return result;
}

}  // namespace

std::vector<std::string> entries(const fs::path& archive, const std::string& suffix) {
    const Archive open(archive);
    std::vector<std::string> names;
    for (const auto& [name, size] : listing(open, archive)) {
        if (lower(name).ends_with(lower(suffix))) {
            names.push_back(printable(name));
        }
    }
    return names;
}

std::vector<std::byte> read_entry(const fs::path& archive, const std::string& entry) {
    const Archive open(archive);
    const auto names = listing(open, archive);
    const auto it = std::find_if(names.begin(), names.end(),
                                 [&](const auto& n) { return lower(n.first) == lower(entry); });
    if (it == names.end()) {
        std::vector<std::string> known;
        for (const auto& [name, size] : names) {
            known.push_back(printable(name));
        }
        fail("{}: no entry {}{}", archive.string(), quote(entry), did_you_mean(entry, known));
    }
    if (it->second > kMaxEntryBytes) {
        fail("{}: entry {} is {} bytes, at most {}", archive.string(), quote(entry), it->second,
             kMaxEntryBytes);
    }
    std::vector<std::byte> bytes(size_t(it->second));
    const bool read =
        unzLocateFile(open.file, it->first.c_str(), 0) == UNZ_OK &&
        unzOpenCurrentFile(open.file) == UNZ_OK &&
        (bytes.empty() ||
         unzReadCurrentFile(open.file, bytes.data(), unsigned(bytes.size())) == int(bytes.size()));
    const bool closed = unzCloseCurrentFile(open.file) == UNZ_OK;  // also checks the CRC
    if (!read || !closed) {
        fail("{}: cannot inflate entry {} (damaged archive)", archive.string(), quote(entry));
    }
    return bytes;
}

}  // namespace sl::pk3
