#include "scenes/pk3.h"

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

// Every entry's name, in archive order.
std::vector<std::string> names(const Archive& archive, const fs::path& path) {
    std::vector<std::string> result;
    for (int status = unzGoToFirstFile(archive.file); status == UNZ_OK;
         status = unzGoToNextFile(archive.file)) {
        char name[1024];
        if (unzGetCurrentFileInfo64(archive.file, nullptr, name, sizeof name, nullptr, 0, nullptr,
                                    0) != UNZ_OK) {
            fail("{}: cannot read the archive's directory", path.string());
        }
        result.emplace_back(name);
    }
    return result;
}

}  // namespace

std::vector<std::string> entries(const fs::path& archive, const std::string& extension) {
    const Archive open(archive);
    std::vector<std::string> found;
    for (const std::string& name : names(open, archive)) {
        if (lower_extension(name) == extension) {
            found.push_back(printable(name));
        }
    }
    return found;
}

std::vector<std::byte> read_entry(const fs::path& archive, const std::string& entry) {
    const Archive open(archive);
    constexpr int kCaseInsensitive = 2;  // minizip's iCaseSensitivity
    if (unzLocateFile(open.file, entry.c_str(), kCaseInsensitive) != UNZ_OK) {
        std::vector<std::string> known;
        for (const std::string& name : names(open, archive)) {
            known.push_back(printable(name));
        }
        fail("{}: no entry {}{}", archive.string(), quote(entry), did_you_mean(entry, known));
    }
    unz_file_info64 info;
    if (unzGetCurrentFileInfo64(open.file, &info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK) {
        fail("{}: cannot read the archive's directory", archive.string());
    }
    if (info.uncompressed_size > kMaxEntryBytes) {
        fail("{}: entry {} is {} bytes, at most {}", archive.string(), quote(entry),
             info.uncompressed_size, kMaxEntryBytes);
    }
    std::vector<std::byte> bytes(size_t(info.uncompressed_size));
    const bool read =
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
