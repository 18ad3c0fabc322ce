// SPDX-License-Identifier: GPL-3.0-or-later
// readMesh maps uncompressed files (src/os/mapped_file.h). A file another process cuts short
// while it is read must end in the same clear error as with read(), not in SIGBUS: here the
// interrupter, asked before the body is parsed, truncates the file to its header.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;
using hyvox::test::TempDir;

// A binary PLY of `quads` quads (2 triangles each) in a row: about 38 bytes per quad.
std::string stripPly(int quads, std::size_t& header_size) {
    const int vertices = 2 * (quads + 1);
    std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(vertices) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(2 * quads) +
        "\nproperty list uchar int vertex_indices\nend_header\n";
    header_size = header.size();
    std::string body;
    auto put = [&](const void* p, std::size_t n) { body.append(static_cast<const char*>(p), n); };
    for (int i = 0; i <= quads; ++i)
        for (float y : {0.0f, 1.0f}) {
            const float v[3] = {float(i), y, 0.5f * float(i % 3)};
            put(v, sizeof v);
        }
    for (int i = 0; i < quads; ++i) {
        const std::uint8_t three = 3;
        const std::int32_t a[3] = {2 * i, 2 * i + 2, 2 * i + 3}, b[3] = {2 * i, 2 * i + 3, 2 * i + 1};
        for (const auto* t : {a, b}) {
            put(&three, 1);
            put(t, 3 * sizeof(std::int32_t));
        }
    }
    return header + body;
}

// Truncates `path` to `size` bytes the first time it is asked after the file is open (the
// read's 0% report comes before that); never says stop.
class Truncator final : public hyvox::Interrupter {
public:
    Truncator(fs::path path, std::size_t size) : path_(std::move(path)), size_(size) {}
    bool wasInterrupted(int percent) override {
        if (percent == 0) return false;
        if (!done_) fs::resize_file(path_, size_);
        done_ = true;
        return false;
    }

private:
    fs::path path_;
    std::size_t size_;
    bool done_ = false;
};

TEST(IoMappedFile, ReadsTheWholeFile) {
    TempDir dir;
    std::size_t header_size = 0;
    const fs::path path = dir.write("strip.ply", stripPly(40000, header_size));
    const hyvox::Mesh mesh = hyvox::readMesh(path.string());
    EXPECT_EQ(mesh.vertexCount(), 80002u);
    ASSERT_EQ(mesh.triangles.size(), 3u * 80000u);
    EXPECT_EQ(mesh.triangles[3 * 79999 + 1], 2u * 39999u + 3u);
    EXPECT_EQ(mesh.positions[3 * 80001], 40000.0f);
}

TEST(IoMappedFile, AFileCutShortWhileReadIsAClearError) {
    TempDir dir;
    std::size_t header_size = 0;
    const fs::path path = dir.write("strip.ply", stripPly(40000, header_size));  // ~1.5 MB
    Truncator truncator(path, header_size);
    try {
        hyvox::readMesh(path.string(), &truncator);
        FAIL() << "expected InvalidInput";
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_NE(std::string(e.what()).find("changed size while it was read"), std::string::npos) << e.what();
    }
    // The guard is per mapping: the next read of the (now short) file is an ordinary error.
    try {
        hyvox::readMesh(path.string());
        FAIL() << "expected InvalidInput";
    } catch (const hyvox::InvalidInput& e) {
        EXPECT_EQ(std::string(e.what()).find("changed size"), std::string::npos) << e.what();
    }
}

}  // namespace
