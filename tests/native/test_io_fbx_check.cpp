// SPDX-License-Identifier: GPL-3.0-or-later
// The FBX container check (src/mesh_io/fbx_check.h), on the binary FBX files the fuzzer starts from
// (tests/fuzz/seeds/fbx/: FBX 7.4 with plain arrays, 7.5 with 64-bit records and zlib
// arrays, written by tests/python/mesh_writers.py): they pass, and each kind of disagreement
// inside the container that assimp reads as another mesh is refused, naming the byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "hyvox/errors.h"
#include "mesh_io/fbx_check.h"

namespace fs = std::filesystem;

namespace {

std::string seed(const char* name) {
    std::ifstream in(fs::path(HYVOX_SOURCE_DIR) / "tests/fuzz/seeds/fbx" / name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string errorOf(const std::string& bytes) {
    try {
        hyvox::mesh_io::checkFbxContainer(bytes.data(), bytes.size(), "m.fbx", 1ull << 30);
    } catch (const hyvox::InvalidInput& e) {
        return e.what();
    }
    return "(no error)";
}

// The byte just after the name `name` of a record: where its properties start.
std::size_t propertiesOf(const std::string& bytes, const std::string& name) {
    const auto at = bytes.find(name);
    EXPECT_NE(at, std::string::npos) << name;
    return at + name.size();
}

#define EXPECT_HAS(TEXT, PART) EXPECT_NE(std::string(TEXT).find(PART), std::string::npos) << (TEXT)

}  // namespace

TEST(IoFbxCheck, ConsistentFilesPass) {
    for (const char* name : {"tetra_7400.fbx", "tetra_7500_zlib.fbx"}) {
        const std::string bytes = seed(name);
        ASSERT_GT(bytes.size(), 100u) << name;
        EXPECT_EQ(errorOf(bytes), "(no error)") << name;
    }
}

// Found by fuzz_fbx_check: a record whose end offset lies inside its own 13-byte header made
// the check's byte counts wrap and read past the file (ASan: heap-buffer-overflow).
TEST(IoFbxCheck, ARecordEndingInsideItsHeaderIsRefused) {
    EXPECT_HAS(errorOf(seed("record_end_inside_its_header.fbx")), "or inside its own header");
}

TEST(IoFbxCheck, DisagreementsAreRefused) {
    const std::string plain = seed("tetra_7400.fbx"), zipped = seed("tetra_7500_zlib.fbx");
    // An array's stored byte length one less than its count says (the damage run's FBX case).
    std::string shorter = plain;
    const std::size_t array = propertiesOf(shorter, "PolygonVertexIndex");  // 'i', count, encoding, length
    ASSERT_EQ(shorter[array], 'i');
    std::uint32_t length;
    std::memcpy(&length, &shorter[array + 9], 4);
    --length;
    std::memcpy(&shorter[array + 9], &length, 4);
    EXPECT_HAS(errorOf(shorter), "an array of 12 values holds 47 bytes, not 48");
    // A count that no longer matches the zlib stream.
    std::string recount = zipped;
    const std::size_t packed = propertiesOf(recount, "Vertices");
    ASSERT_EQ(recount[packed], 'd');
    recount[packed + 1] = char(recount[packed + 1] + 1);
    EXPECT_HAS(errorOf(recount), "a compressed array that does not inflate to its 104 bytes");
    // A record's end past its parent's, and properties whose length disagrees with the header.
    std::string outside = plain;
    std::uint32_t end;
    std::memcpy(&end, &outside[27], 4);
    end = std::uint32_t(outside.size() + 10);
    std::memcpy(&outside[27], &end, 4);
    EXPECT_HAS(errorOf(outside), "outside its parent");
    std::string unknown = plain;
    unknown[array] = 'q';
    EXPECT_HAS(errorOf(unknown), "a property of unknown type");
    EXPECT_HAS(errorOf(plain.substr(0, plain.size() - 13)), "a record header runs past its end");  // no closing record
    EXPECT_HAS(errorOf("; FBX 7.4.0 project file\nFBXHeaderExtension:  {\n}\n"), "ASCII FBX is not read");
    EXPECT_HAS(errorOf("not an FBX file at all, just text"), "is not a binary FBX file");
    std::string version = plain;
    version[23] = 0;  // 7400 -> 7168 still 7.x; 6100 is not
    const std::uint32_t six = 6100;
    std::memcpy(&version[23], &six, 4);
    EXPECT_HAS(errorOf(version), "version 6100 (only FBX 7.x is read)");
}
