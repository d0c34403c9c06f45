#include "core/output_files.h"

#include <unistd.h>

#include <fstream>

#include "core/error.h"

namespace sl {

namespace fs = std::filesystem;

OutputFiles::OutputFiles(fs::path directory) : directory_(std::move(directory)) {
    std::error_code ec;
    for (fs::path p = fs::absolute(directory_, ec); !p.empty() && !fs::exists(p, ec);
         p = p.parent_path()) {
        created_.insert(created_.begin(), p);
        if (p == p.parent_path()) {
            break;
        }
    }
    fs::create_directories(directory_, ec);
    if (ec || !fs::is_directory(directory_)) {
        fail("{}: cannot create output directory: {}", directory_.string(), ec.message());
    }
}

OutputFiles::~OutputFiles() {
    for (const auto& [temporary, final_path] : staged_) {
        std::error_code ec;
        fs::remove(temporary, ec);
    }
    if (!committed_) {
        for (auto p = created_.rbegin(); p != created_.rend(); ++p) {
            std::error_code ec;
            fs::remove(*p, ec);  // only when empty: another writer may have used it meanwhile
        }
    }
}

void OutputFiles::add(const std::string& name, const std::function<void(const fs::path&)>& write) {
    const fs::path final_path = directory_ / name;
    std::error_code ec;
    if (name.empty() || fs::is_directory(final_path, ec)) {
        fail("{}: cannot write a file there: it is a directory (expected a file's path)",
             final_path.string());
    }
    const fs::path temporary =
        directory_ / fmt::format(".{}.{}.tmp", name, static_cast<long>(::getpid()));
    staged_.emplace_back(temporary, final_path);
    write(temporary);
}

void OutputFiles::add_text(const std::string& name, const std::string& text) {
    add(name, [&](const fs::path& path) {
        std::ofstream out(path, std::ios::binary);
        out << text;
        out.close();
        if (!out) {
            fail("{}: cannot write", path.string());
        }
    });
}

std::vector<fs::path> OutputFiles::commit() {
    std::vector<fs::path> written;
    for (const auto& [temporary, final_path] : staged_) {
        std::error_code ec;
        fs::rename(temporary, final_path, ec);
        if (ec) {
            fail("{}: cannot rename into place: {}", final_path.string(), ec.message());
        }
        written.push_back(final_path);
    }
    committed_ = true;
    staged_.clear();
    return written;
}

}  // namespace sl
