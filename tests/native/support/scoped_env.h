// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Sets an environment variable for one scope and restores what was there before, for the
// tests of settings read from the environment (HYVOX_SHADER_DIR, HYVOX_GL_TILE_BYTES, ...).
#include <cstdlib>
#include <string>

namespace hyvox::test {

class ScopedEnv {
public:
    ScopedEnv(const char* name, const std::string& value) : name_(name) {
        if (const char* old = std::getenv(name))
            old_ = old, had_ = true;
        setenv(name, value.c_str(), 1);
    }
    ~ScopedEnv() {
        if (had_)
            setenv(name_, old_.c_str(), 1);
        else
            unsetenv(name_);
    }
    ScopedEnv(const ScopedEnv&) = delete;
    ScopedEnv& operator=(const ScopedEnv&) = delete;

private:
    const char* name_;
    std::string old_;
    bool had_ = false;
};

}  // namespace hyvox::test
