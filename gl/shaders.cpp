#include "gl/shaders.h"

#include <optional>
#include <set>
#include <sstream>

#include "core/error.h"
#include "gl/embedded_files.h"

namespace sl::gl {

namespace {

std::string_view embedded(const std::string& path) {
    const auto& files = embedded_files();
    const auto it = files.find(path);
    if (it == files.end()) {
        fail("shader file '{}' is not embedded in the binary", path);
    }
    return it->second;
}

void expand(const std::string& path, std::set<std::string>& stack, std::string& out) {
    if (!stack.insert(path).second) {
        fail("shader file '{}' includes itself", path);
    }
    std::istringstream in{std::string(embedded(path))};
    std::string line;
    while (std::getline(in, line)) {
        constexpr std::string_view kInclude = "#include \"";
        if (line.starts_with(kInclude) && line.back() == '"') {
            expand(line.substr(kInclude.size(), line.size() - kInclude.size() - 1), stack, out);
        } else {
            out += line;
            out += '\n';
        }
    }
    stack.erase(path);
}

// The status flag of a shader or program; on failure, its info log.
template <typename GetIv, typename GetInfoLog>
std::optional<std::string> failure_log(GLuint id, GLenum status, GetIv get_iv, GetInfoLog get_log) {
    GLint ok = GL_FALSE;
    get_iv(id, status, &ok);
    if (ok) {
        return std::nullopt;
    }
    GLint length = 0;
    get_iv(id, GL_INFO_LOG_LENGTH, &length);
    std::string log(size_t(std::max(length, 1)), '\0');
    get_log(id, length, nullptr, log.data());
    return std::string(log.c_str());
}

Shader compile(const ShaderStage& stage, const std::vector<std::string>& defines) {
    const std::string source = shader_source(stage.path, defines);
    Shader shader(GL.CreateShader(stage.type));
    const char* text = source.c_str();
    GL.ShaderSource(shader.id(), 1, &text, nullptr);
    GL.CompileShader(shader.id());
    if (const auto log =
            failure_log(shader.id(), GL_COMPILE_STATUS, GL.GetShaderiv, GL.GetShaderInfoLog)) {
        fail("{}: shader does not compile: {}", stage.path, *log);
    }
    return shader;
}

}  // namespace

std::string shader_source(const std::string& path, const std::vector<std::string>& defines) {
    std::set<std::string> stack;
    std::string expanded;
    expand(path, stack, expanded);
    if (!expanded.starts_with("#version")) {
        fail("shader file '{}' must begin with a #version line", path);
    }
    std::string define_lines;
    for (const std::string& define : defines) {
        define_lines += "#define " + define + "\n";
    }
    const size_t after_version = expanded.find('\n') + 1;
    expanded.insert(after_version, define_lines);
    return expanded;
}

Program create_program(const std::vector<ShaderStage>& stages,
                       const std::vector<std::string>& defines) {
    Program program(GL.CreateProgram());
    std::vector<Shader> shaders;
    std::string names;
    for (const ShaderStage& stage : stages) {
        shaders.push_back(compile(stage, defines));
        GL.AttachShader(program.id(), shaders.back().id());
        names += (names.empty() ? "" : " + ") + stage.path;
    }
    GL.LinkProgram(program.id());
    if (const auto log =
            failure_log(program.id(), GL_LINK_STATUS, GL.GetProgramiv, GL.GetProgramInfoLog)) {
        fail("{}: program does not link: {}", names, *log);
    }
    program.label(names);
    return program;
}

void dispatch_compute(glm::ivec3 threads, glm::ivec3 local) {
    const glm::ivec3 groups = (threads + local - 1) / local;
    GL.DispatchCompute(GLuint(groups.x), GLuint(groups.y), GLuint(groups.z));
    GL.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT |
                     GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace sl::gl
