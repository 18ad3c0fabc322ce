// SPDX-License-Identifier: GPL-3.0-or-later
// The headless GL layer: EGL devices, the worker thread and its context, RAII objects,
// KHR_debug errors as exceptions, embedded shaders, and the binding points shared by GLSL
// and C++ (the linked programs must report exactly the values C++ binds).
#include <gtest/gtest.h>

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "gl/binding_points.h"
#include "gl/egl_device.h"
#include "gl/gl_debug.h"
#include "gl/gl_objects.h"
#include "gl/gl_worker.h"
#include "gl/shader_library.h"
#include "hyvox/errors.h"
#include "support/temp_dir.h"

namespace hyvox::gl {
namespace {

TEST(GlLayer, ListsASoftwareDevice) {
    const auto devices = listEglDevices();
    ASSERT_FALSE(devices.empty());
    bool software = false;
    for (const auto& d : devices) software |= d.software;
    EXPECT_TRUE(software) << "Mesa's software EGL device (llvmpipe) is the CI fallback";
}

TEST(GlLayer, WorkerHasAGl45CoreContext) {
    GlWorker& worker = GlWorker::get();
    const auto version = worker.run([] { return epoxy_gl_version(); });
    EXPECT_GE(version, 45);
    EXPECT_FALSE(worker.renderer().empty());
    // The same selection returns the same worker (one context for the library's lifetime).
    EXPECT_EQ(&GlWorker::get(), &worker);
    // Work runs on the worker's own thread, not the caller's.
    EXPECT_NE(worker.run([] { return std::this_thread::get_id(); }), std::this_thread::get_id());
}

TEST(GlLayer, CallerContextIsLeftAlone) {
    // A host with its own context current on this thread (as Blender's UI thread has).
    GlWorker::get();  // the worker exists before and after
    EglContext host("software");
    const EGLContext mine = eglGetCurrentContext();
    ASSERT_NE(mine, EGL_NO_CONTEXT);
    GlWorker::get().run([] {
        Buffer b(64, nullptr);
        b.clearToZero();
        glFinish();
    });
    EXPECT_EQ(eglGetCurrentContext(), mine);
}

TEST(GlLayer, ExceptionsTravelBackToTheCaller) {
    EXPECT_THROW(GlWorker::get().run([]() -> int { throw InvalidInput("from the GL thread"); }), InvalidInput);
    EXPECT_EQ(GlWorker::get().run([] { return 7; }), 7);  // and the worker carries on
}

TEST(GlLayer, DriverErrorsBecomeExceptions) {
    GlWorker::get().run([] {
        checkGl("clean state");
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1u << 20, 12345);  // invalid index and name
        try {
            checkGl("a deliberate error");
            ADD_FAILURE() << "expected BackendError";
        } catch (const BackendError& e) {
            EXPECT_NE(std::string(e.what()).find("a deliberate error"), std::string::npos) << e.what();
        }
        checkGl("cleared after throwing");
    });
}

TEST(GlLayer, ObjectsAreMoveOnlyOwners) {
    GlWorker::get().run([] {
        GLuint id = 0;
        {
            Buffer a(256, nullptr);
            id = a.id();
            EXPECT_TRUE(glIsBuffer(id));
            Buffer b = std::move(a);
            EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from owner is what is tested
            EXPECT_EQ(b.id(), id);
            EXPECT_TRUE(glIsBuffer(id));
        }
        EXPECT_FALSE(glIsBuffer(id));
        checkGl("objects");
    });
    static_assert(!std::is_copy_constructible_v<Buffer> && std::is_move_constructible_v<Buffer>);
    static_assert(!std::is_copy_constructible_v<Program> && std::is_move_constructible_v<Program>);
}

TEST(GlLayer, CompileErrorsNameTheFileAndQuoteTheLog) {
    const test::TempDir temp;
    const std::string dir = temp.path.string();
    std::filesystem::create_directories(temp.path / "common");
    std::ofstream(temp.path / "common" / "helper.glsl")
        << "// SPDX-License-Identifier: GPL-3.0-or-later\nfloat helper() { return 1.0 }\n";
    std::ofstream(temp.path / "broken.comp")
        << "// SPDX-License-Identifier: GPL-3.0-or-later\n#include "
           "\"common/helper.glsl\"\nlayout(local_size_x = 1) in;\nvoid main() {}\n";
    GlWorker::get().run([&] {
        try {
            buildProgram({{GL_COMPUTE_SHADER, "broken.comp"}}, "", dir);
            ADD_FAILURE() << "expected BackendError";
        } catch (const BackendError& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find(dir + "/broken.comp"), std::string::npos) << what;
            EXPECT_NE(what.find("1=common/helper.glsl"), std::string::npos) << what;
            EXPECT_NE(what.find("1:2"), std::string::npos) << "log points at source 1, line 2: " << what;
        }
    });
}

TEST(GlLayer, EmbeddedShadersMatchTheSourceTree) {
    const auto& embedded = embeddedShaders();
    ASSERT_TRUE(embedded.count("common/bindings.glsl"));
    for (const auto& [name, text] : embedded) {
        std::ifstream file(std::string(HYVOX_SOURCE_SHADERS) + "/" + name, std::ios::binary);
        std::ostringstream disk;
        disk << file.rdbuf();
        EXPECT_EQ(disk.str(), text) << name << " is stale: rebuild";
        // Every file carries its licence line (the loader prepends #version).
        EXPECT_EQ(text.rfind("// SPDX-License-Identifier: GPL-3.0-or-later", 0), 0u) << name;
    }
}

// Binding points and uniform locations the drivers assign must equal the C++ values.
GLint blockBinding(GLuint program, const char* block) {
    const GLuint index = glGetProgramResourceIndex(program, GL_SHADER_STORAGE_BLOCK, block);
    if (index == GL_INVALID_INDEX) return -1;
    const GLenum property = GL_BUFFER_BINDING;
    GLint value = -1;
    glGetProgramResourceiv(program, GL_SHADER_STORAGE_BLOCK, index, 1, &property, 1, nullptr, &value);
    return value;
}

TEST(GlLayer, BindingPointsMatchBetweenGlslAndCpp) {
    // C++ includes the very same bindings.glsl, so only the driver can disagree: what the
    // linked programs report must be the values C++ binds and sets.
    GlWorker::get().run([] {
        const std::string defines =
            "#define HYVOX_THIN 0\n#define HYVOX_VOXEL_LIST 1\n#define HYVOX_FROM_LARGE_LIST 1\n";
        const Program classify = buildProgram({{GL_COMPUTE_SHADER, "hybrid/classify.comp"}}, defines, "");
        EXPECT_EQ(blockBinding(classify.id(), "Bits"), HYVOX_SSBO_BITS);
        EXPECT_EQ(blockBinding(classify.id(), "Vertices"), HYVOX_SSBO_VERTICES);
        EXPECT_EQ(blockBinding(classify.id(), "Triangles"), HYVOX_SSBO_TRIANGLES);
        EXPECT_EQ(blockBinding(classify.id(), "LargeTriangles"), HYVOX_SSBO_LARGE);
        EXPECT_EQ(blockBinding(classify.id(), "DrawCommand"), HYVOX_SSBO_DRAW);
        EXPECT_EQ(blockBinding(classify.id(), "VoxelList"), HYVOX_SSBO_VOXEL_LIST);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "gridDims"), HYVOX_LOC_GRID_DIMS);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "slabX"), HYVOX_LOC_SLAB);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "triangleCount"), HYVOX_LOC_TRIANGLE_COUNT);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "cutoff"), HYVOX_LOC_CUTOFF);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "voxelListCapacity"), HYVOX_LOC_LIST_CAPACITY);
        EXPECT_EQ(glGetUniformLocation(classify.id(), "chunkSide"), HYVOX_LOC_CHUNK_SIDE);
        GLint local[3] = {0, 0, 0};
        glGetProgramiv(classify.id(), GL_COMPUTE_WORK_GROUP_SIZE, local);
        EXPECT_EQ(local[0], HYVOX_LOCAL_SIZE);

        const Program raster = buildProgram({{GL_VERTEX_SHADER, "hybrid/fragment_parallel.vert"},
                                             {GL_GEOMETRY_SHADER, "hybrid/fragment_parallel.geom"},
                                             {GL_FRAGMENT_SHADER, "hybrid/fragment_parallel.frag"}},
                                            defines, "");
        EXPECT_EQ(blockBinding(raster.id(), "Bits"), HYVOX_SSBO_BITS);
        EXPECT_EQ(blockBinding(raster.id(), "LargeTriangles"), HYVOX_SSBO_LARGE);
        EXPECT_EQ(glGetUniformLocation(raster.id(), "viewportSize"), HYVOX_LOC_VIEWPORT);
        checkGl("binding queries");
    });
}

}  // namespace
}  // namespace hyvox::gl
