// SPDX-License-Identifier: GPL-3.0-or-later
// Cancelling readMesh (issue 16): the interrupter is asked at milestones inside every reader
// (PLY ASCII and binary, OBJ, gzip, assimp), so a stop asked for in the middle of a large
// file ends the read with hyvox::Cancelled, and a reader that is never stopped returns the
// same mesh as without an interrupter.
#include <gtest/gtest.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"
#include "support/temp_dir.h"

namespace {

namespace fs = std::filesystem;
using hyvox::test::TempDir;

// Says stop at its `stop_at`-th question (0 = never) and counts every question.
class CountingInterrupter final : public hyvox::Interrupter {
public:
    explicit CountingInterrupter(int stop_at) : stop_at_(stop_at) {}
    bool wasInterrupted(int) override { return ++asked_ == stop_at_; }
    int asked() const { return asked_; }

private:
    int stop_at_;
    int asked_ = 0;
};

// A strip of `quads` unit squares: 2·(quads+1) vertices, 2·quads triangles.
constexpr int kQuads = 150000;  // 300k faces: several 64k-record chunks per element

std::string asciiPly() {
    std::string out = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(2 * (kQuads + 1)) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(2 * kQuads) +
        "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i <= kQuads; ++i) out += std::to_string(i) + " 0 0\n" + std::to_string(i) + " 1 0\n";
    for (int i = 0; i < kQuads; ++i) {
        const int a = 2 * i;
        out += "3 " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 1) + "\n";
        out += "3 " + std::to_string(a + 1) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
    }
    return out;
}

std::string binaryPly() {
    std::string out = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(2 * (kQuads + 1)) +
        "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(2 * kQuads) +
        "\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
    for (int i = 0; i <= kQuads; ++i)
        for (float y : {0.0f, 1.0f}) {
            const float v[3] = {float(i), y, 0.0f};
            put(v, sizeof v);
        }
    for (int i = 0; i < kQuads; ++i) {
        const std::int32_t a = 2 * i;
        for (const std::array<std::int32_t, 3>& f :
             {std::array<std::int32_t, 3>{a, a + 2, a + 1}, {a + 1, a + 2, a + 3}}) {
            const unsigned char three = 3;
            put(&three, 1);
            put(f.data(), sizeof f);
        }
    }
    return out;
}

std::string obj() {
    std::string out;
    for (int i = 0; i <= kQuads; ++i) out += "v " + std::to_string(i) + " 0 0\nv " + std::to_string(i) + " 1 0\n";
    for (int i = 0; i < kQuads; ++i) {
        const int a = 2 * i + 1;  // OBJ counts from 1
        out += "f " + std::to_string(a) + " " + std::to_string(a + 2) + " " + std::to_string(a + 1) + "\n";
        out += "f " + std::to_string(a + 1) + " " + std::to_string(a + 2) + " " + std::to_string(a + 3) + "\n";
    }
    return out;
}

std::string stl() {  // ASCII STL, read through assimp
    std::string out = "solid strip\n";
    for (int i = 0; i < 2000; ++i)
        out += "facet normal 0 0 1\nouter loop\nvertex " + std::to_string(i) + " 0 0\nvertex " + std::to_string(i + 1) +
            " 0 0\nvertex " + std::to_string(i) + " 1 0\nendloop\nendfacet\n";
    return out + "endsolid strip\n";
}

fs::path writeGzip(const TempDir& dir, const std::string& name, const std::string& data) {
    const fs::path path = dir.path / name;
    gzFile gz = gzopen(path.c_str(), "wb");
    EXPECT_NE(gz, nullptr);
    EXPECT_EQ(gzwrite(gz, data.data(), unsigned(data.size())), int(data.size()));
    gzclose(gz);
    return path;
}

struct Case {
    std::string file;
    std::string text;
};

void expectCancelledAtEveryMilestone(const fs::path& path, int min_milestones) {
    const hyvox::Mesh expected = hyvox::readMesh(path.string());
    CountingInterrupter never(0);
    const hyvox::Mesh read = hyvox::readMesh(path.string(), &never);
    EXPECT_EQ(read.positions, expected.positions) << path;
    EXPECT_EQ(read.triangles, expected.triangles) << path;
    EXPECT_GE(never.asked(), min_milestones) << path;
    // A stop asked at the first, a middle and the last milestone ends the read every time.
    for (int stop_at : {1, never.asked() / 2 + 1, never.asked()}) {
        CountingInterrupter stopping(stop_at);
        EXPECT_THROW(hyvox::readMesh(path.string(), &stopping), hyvox::Cancelled) << path << " at " << stop_at;
        EXPECT_EQ(stopping.asked(), stop_at) << "read on after the stop: " << path;
    }
}

TEST(MeshReadCancel, EveryReaderStopsAtItsMilestones) {
    TempDir dir;
    // 300k vertices and 300k faces: at least 2 × 4 chunks of 64k records (or lines).
    expectCancelledAtEveryMilestone(dir.write("strip.ply", asciiPly()), 8);
    expectCancelledAtEveryMilestone(dir.write("strip_binary.ply", binaryPly()), 8);
    expectCancelledAtEveryMilestone(dir.write("strip.obj", obj()), 8);
    // gzip: every MiB of output (the ASCII PLY is ~9 MiB) and then the PLY's chunks.
    expectCancelledAtEveryMilestone(writeGzip(dir, "strip.ply.gz", asciiPly()), 8 + 8);
    expectCancelledAtEveryMilestone(dir.write("strip.stl", stl()), 2);
}

}  // namespace
