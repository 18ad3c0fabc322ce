// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Move-only owners of GL object names, created with direct state access (glCreate*).
// They must be created and destroyed on the GL worker thread (inside GlWorker::run).
// Each one is counted while it holds a name (object_counts.h).
#include <epoxy/gl.h>

#include <cstddef>
#include <utility>

#include "gl/object_counts.h"

namespace hyvox::gl {

template <typename Traits>
class GlObject {
public:
    GlObject() : id_(Traits::create()) { counted(); }
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    GLuint id() const { return id_; }

protected:
    explicit GlObject(GLuint adopted) : id_(adopted) { counted(); }
    void reset() {
        if (id_) {
            Traits::destroy(id_);
            countDeleted(Traits::kKind);
        }
        id_ = 0;
    }

private:
    void counted() const {
        if (id_) countCreated(Traits::kKind);
    }
    GLuint id_ = 0;
};

struct BufferTraits {
    static constexpr GlKind kKind = GlKind::Buffer;
    static GLuint create() {
        GLuint id = 0;
        glCreateBuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteBuffers(1, &id); }
};
struct VertexArrayTraits {
    static constexpr GlKind kKind = GlKind::VertexArray;
    static GLuint create() {
        GLuint id = 0;
        glCreateVertexArrays(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteVertexArrays(1, &id); }
};
struct FramebufferTraits {
    static constexpr GlKind kKind = GlKind::Framebuffer;
    static GLuint create() {
        GLuint id = 0;
        glCreateFramebuffers(1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteFramebuffers(1, &id); }
};
struct ProgramTraits {
    static constexpr GlKind kKind = GlKind::Program;
    static GLuint create() { return glCreateProgram(); }
    static void destroy(GLuint id) { glDeleteProgram(id); }
};
struct TimerQueryTraits {
    static constexpr GlKind kKind = GlKind::Query;
    static GLuint create() {
        GLuint id = 0;
        glCreateQueries(GL_TIME_ELAPSED, 1, &id);
        return id;
    }
    static void destroy(GLuint id) { glDeleteQueries(1, &id); }
};

// An immutable-storage buffer (glNamedBufferStorage).
class Buffer : public GlObject<BufferTraits> {
public:
    Buffer() = default;
    Buffer(std::size_t bytes, const void* data, GLbitfield flags = GL_DYNAMIC_STORAGE_BIT) {
        glNamedBufferStorage(id(), GLsizeiptr(bytes ? bytes : 4), data, flags);
        size_ = bytes;
    }
    std::size_t size() const { return size_; }
    void bindBase(GLenum target, GLuint index) const { glBindBufferBase(target, index, id()); }
    void clearToZero() const {
        const GLuint zero = 0;
        glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
    void upload(std::size_t offset, std::size_t bytes, const void* data) const {
        glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
    }
    void download(std::size_t offset, std::size_t bytes, void* data) const {
        glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
    }

private:
    std::size_t size_ = 0;
};

using VertexArray = GlObject<VertexArrayTraits>;
using Framebuffer = GlObject<FramebufferTraits>;

class Shader {
public:
    explicit Shader(GLenum stage) : id_(glCreateShader(stage)) {
        if (id_) countCreated(GlKind::Shader);
    }
    ~Shader() {
        if (id_) {
            glDeleteShader(id_);
            countDeleted(GlKind::Shader);
        }
    }
    Shader(Shader&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Shader& operator=(Shader&& other) noexcept {
        std::swap(id_, other.id_);
        return *this;
    }
    Shader(const Shader&) = delete;
    Shader& operator=(const Shader&) = delete;
    GLuint id() const { return id_; }

private:
    GLuint id_ = 0;
};

class Program : public GlObject<ProgramTraits> {
public:
    Program() = default;
    void use() const { glUseProgram(id()); }
};

// GL_TIME_ELAPSED around one pass: begin(), the pass, end(); milliseconds() waits for the GPU.
class TimerQuery : public GlObject<TimerQueryTraits> {
public:
    void begin() const { glBeginQuery(GL_TIME_ELAPSED, id()); }
    static void end() { glEndQuery(GL_TIME_ELAPSED); }
    double milliseconds() const {
        GLuint64 ns = 0;
        glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &ns);
        return double(ns) * 1e-6;
    }
};

}  // namespace hyvox::gl
