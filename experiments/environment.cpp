#include "experiments/environment.h"

#include <unistd.h>

#include <CGAL/version.h>
#include <OpenEXR/OpenEXRConfig.h>
#include <embree3/rtcore_config.h>
#include <tbb/version.h>
#include <toml++/toml.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <glm/detail/setup.hpp>

#ifndef SHAFTLAB_SOURCE_DIR
#error "SHAFTLAB_SOURCE_DIR must be defined by the build"
#endif

namespace sl::experiments {

namespace {

using Json = nlohmann::ordered_json;

// The output of a command, trimmed; empty when it fails.
std::string command_output(const std::string& command) {
    std::string output;
    if (FILE* pipe = popen((command + " 2>/dev/null").c_str(), "r")) {
        char buffer[256];
        while (fgets(buffer, sizeof buffer, pipe)) {
            output += buffer;
        }
        if (pclose(pipe) != 0) {
            return {};
        }
    }
    while (!output.empty() && (output.back() == '\n' || output.back() == ' ')) {
        output.pop_back();
    }
    return output;
}

std::string proc_field(const char* file, const std::string& key) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        if (line.starts_with(key)) {
            const size_t colon = line.find_first_of(":=");
            std::string value = colon == std::string::npos ? "" : line.substr(colon + 1);
            value.erase(0, value.find_first_not_of(" \t\""));
            while (!value.empty() && (value.back() == '"' || value.back() == ' ')) {
                value.pop_back();
            }
            return value;
        }
    }
    return {};
}

}  // namespace

Json environment(const Experiment& x, const std::vector<StoredRow>& rows) {
    const std::string source = SHAFTLAB_SOURCE_DIR;
    const std::string sha = command_output("git -C '" + source + "' rev-parse HEAD");
    const std::string status = command_output("git -C '" + source + "' status --porcelain");
    char host[256] = {};
    gethostname(host, sizeof host - 1);
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    Json gl = Json::object();
    if (!rows.empty()) {
        gl = {{"vendor", rows.front().row.value("gl_vendor", "")},
              {"renderer", rows.front().row.value("gl_renderer", "")},
              {"version", rows.front().row.value("gl_version", "")}};
    }
    return {
        {"date", date},
        {"host", host},
        {"os", proc_field("/etc/os-release", "PRETTY_NAME")},
        {"cpu",
         {{"model", proc_field("/proc/cpuinfo", "model name")},
          {"cores", std::thread::hardware_concurrency()},
          {"memory", proc_field("/proc/meminfo", "MemTotal")}}},
        {"gl", gl},
        {"compiler",
         {{"id", SHAFTLAB_CXX_COMPILER},
          {"flags", SHAFTLAB_CXX_FLAGS},
          {"build_type", SHAFTLAB_BUILD_TYPE}}},
        {"libraries",
         {{"embree", RTC_VERSION_STRING},
          {"cgal", CGAL_VERSION_STR},
          {"openexr", OPENEXR_VERSION_STRING},
          {"tbb", fmt::format("{}.{}", TBB_VERSION_MAJOR, TBB_VERSION_MINOR)},
          {"glm", GLM_VERSION},
          {"tomlplusplus", fmt::format("{}.{}.{}", TOML_LIB_MAJOR, TOML_LIB_MINOR, TOML_LIB_PATCH)},
          {"fmt", FMT_VERSION},
          {"nlohmann_json",
           fmt::format("{}.{}.{}", NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                       NLOHMANN_JSON_VERSION_PATCH)}}},
        {"git",
         {{"sha", sha.empty() ? Json() : Json(sha)},
          {"dirty", sha.empty() ? Json() : Json(!status.empty())}}},
        {"experiment",
         {{"name", x.name},
          {"file", x.source.string()},
          {"text", x.text},
          {"overrides", x.overrides},
          {"effective", x.effective}}},
        {"rows", rows.size()},
    };
}

}  // namespace sl::experiments
