// SPDX-License-Identifier: GPL-3.0-or-later
#include "command_support.h"

#include <filesystem>

#include "hyvox/errors.h"

namespace hyvox::cli {

std::unique_ptr<tbb::global_control> limitThreads(int threads) {
    if (threads <= 0) return nullptr;
    return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

void checkOutputFolder(const std::string& path, const char* what) {
    namespace fs = std::filesystem;
    std::error_code error;
    if (fs::is_directory(fs::path(path), error))
        throw InvalidInput(std::string("cannot write ") + what + " '" + path + "': it is a folder");
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    if (!fs::is_directory(folder, error))
        throw InvalidInput(std::string("cannot write ") + what + " '" + path + "': folder '" + folder.string() +
                           "' does not exist");
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace hyvox::cli
