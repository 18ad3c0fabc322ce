// SPDX-License-Identifier: GPL-3.0-or-later
#include "gl/shader_library.h"

#include <fstream>
#include <set>
#include <sstream>

#include "hyvox/errors.h"

namespace hyvox::gl {
namespace {

void appendResolved(const std::string& name, const std::string& dir, ResolvedSource& out, std::set<std::string>& seen,
                    int depth) {
    if (depth > 16) throw BackendError("shader include depth exceeded at '" + name + "'");
    if (!seen.insert(name).second) return;  // include once
    const int number = int(out.files.size());
    out.files.push_back(name);
    std::istringstream in(shaderText(name, dir));
    std::string line;
    int line_no = 0;
    out.text += "#line 1 " + std::to_string(number) + "\n";
    while (std::getline(in, line)) {
        ++line_no;
        const auto start = line.find_first_not_of(" \t");
        if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
            const auto open = line.find('"', start);
            const auto close = open == std::string::npos ? open : line.find('"', open + 1);
            if (close == std::string::npos)
                throw BackendError("shader '" + name + "' line " + std::to_string(line_no) + ": malformed #include");
            appendResolved(line.substr(open + 1, close - open - 1), dir, out, seen, depth + 1);
            out.text += "#line " + std::to_string(line_no + 1) + " " + std::to_string(number) + "\n";
            continue;
        }
        out.text += line;
        out.text += '\n';
    }
}

std::string stageName(GLenum stage) {
    switch (stage) {
        case GL_COMPUTE_SHADER: return "compute";
        case GL_VERTEX_SHADER: return "vertex";
        case GL_TESS_CONTROL_SHADER: return "tessellation control";
        case GL_TESS_EVALUATION_SHADER: return "tessellation evaluation";
        case GL_GEOMETRY_SHADER: return "geometry";
        case GL_FRAGMENT_SHADER: return "fragment";
        default: return "shader";
    }
}

std::string fileList(const std::vector<std::string>& files) {
    std::string text;
    for (std::size_t i = 0; i < files.size(); ++i) text += (i ? ", " : "") + std::to_string(i) + "=" + files[i];
    return text;
}

}  // namespace

std::string shaderText(const std::string& name, const std::string& dir) {
    if (dir.empty()) {
        const auto& embedded = embeddedShaders();
        const auto found = embedded.find(name);
        if (found == embedded.end()) throw BackendError("shader '" + name + "' is not embedded in this build");
        return found->second;
    }
    const std::string path = dir + "/" + name;
    std::ifstream file(path, std::ios::binary);
    if (!file) throw BackendError("cannot read shader '" + path + "' (shader folder from GlOptions::shader_dir)");
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

ResolvedSource resolveShader(const std::string& name, const std::string& dir, const std::string& defines) {
    ResolvedSource out;
    out.text = "#version 450 core\n" + defines;
    std::set<std::string> seen;
    appendResolved(name, dir, out, seen, 0);
    return out;
}

Program buildProgram(const std::vector<ShaderStage>& stages, const std::string& defines, const std::string& dir) {
    // Errors name the file where it was read: the folder given, or the embedded shaders/.
    const std::string folder = dir.empty() ? std::string("shaders") : dir;
    Program program;
    std::vector<Shader> shaders;
    for (const auto& s : stages) {
        const ResolvedSource source = resolveShader(s.file, dir, defines);
        Shader shader(s.stage);
        const char* text = source.text.c_str();
        glShaderSource(shader.id(), 1, &text, nullptr);
        glCompileShader(shader.id());
        GLint ok = GL_FALSE;
        glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLint length = 0;
            glGetShaderiv(shader.id(), GL_INFO_LOG_LENGTH, &length);
            std::string log(std::size_t(length > 0 ? length : 1), '\0');
            glGetShaderInfoLog(shader.id(), GLsizei(log.size()), nullptr, log.data());
            throw BackendError("compiling " + stageName(s.stage) + " shader " + folder + "/" + s.file +
                               " failed (source strings: " + fileList(source.files) + "):\n" + log.c_str());
        }
        glAttachShader(program.id(), shader.id());
        shaders.push_back(std::move(shader));
    }
    glLinkProgram(program.id());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    for (const auto& shader : shaders) glDetachShader(program.id(), shader.id());
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(program.id(), GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(length > 0 ? length : 1), '\0');
        glGetProgramInfoLog(program.id(), GLsizei(log.size()), nullptr, log.data());
        std::string names;
        for (const auto& s : stages) names += (names.empty() ? "" : " + ") + folder + "/" + s.file;
        throw BackendError("linking " + names + " failed:\n" + log.c_str());
    }
    return program;
}

const Program& ProgramCache::get(const std::vector<ShaderStage>& stages, const std::string& defines,
                                 const std::string& dir) {
    std::string key = defines;
    for (const auto& s : stages) key += "|" + std::to_string(s.stage) + ":" + s.file;
    if (!dir.empty()) return uncached_[key] = buildProgram(stages, defines, dir);
    auto found = programs_.find(key);
    if (found != programs_.end()) return found->second;
    return programs_.emplace(key, buildProgram(stages, defines, dir)).first->second;
}

}  // namespace hyvox::gl
