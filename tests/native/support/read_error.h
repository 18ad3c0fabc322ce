// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// What readMesh says about a file, for the reader tests that expect it to refuse one.
#include <gtest/gtest.h>

#include <exception>
#include <filesystem>
#include <string>

#include "hyvox/errors.h"
#include "hyvox/mesh_io.h"

namespace hyvox::test {

// The InvalidInput message readMesh gives, "(no error)" when it reads the file, or the
// name of any other exception (which is itself a failure of the reader's contract).
inline std::string readErrorOf(const std::filesystem::path& path) {
    try {
        hyvox::readMesh(path.string());
    } catch (const hyvox::InvalidInput& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("(wrong exception) ") + e.what();
    }
    return "(no error)";
}

}  // namespace hyvox::test

// Expects readMesh(FILE) to throw InvalidInput whose message names the file and holds each
// of the given parts.
#define EXPECT_READ_ERROR(FILE, ...)                                                                            \
    do {                                                                                                        \
        const std::filesystem::path& file_ = (FILE);                                                            \
        const std::string message_ = hyvox::test::readErrorOf(file_);                                           \
        EXPECT_NE(message_.find(file_.filename().string()), std::string::npos) << message_;                     \
        for (const char* part_ : {__VA_ARGS__}) EXPECT_NE(message_.find(part_), std::string::npos) << message_; \
    } while (0)
