// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A helper program run beside this process, for work that must not be able to end it (the
// assimp reader: assimp_reader.h). Started with posix_spawn, never fork: the caller may be
// Blender or a Python process with GL contexts and TBB threads, where a forked copy could
// deadlock on a lock another thread held; posix_spawn execs at once and copies nothing.
#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace hyvox::os {

class ChildProcess {
public:
    // Starts `program` with `args` (args[0] is the name it is given). Its standard input is a
    // socket this process writes (send() with MSG_NOSIGNAL: a child that died is an error
    // code, never a SIGPIPE here), its standard output and error are pipes this process
    // reads; no other descriptor is passed on. Every signal is at its default and unblocked
    // in the child, which runs in a process group of its own (a Ctrl-C at the terminal
    // reaches this process only, which then ends the child). A program file without its
    // execute bit (unpacked from a zip, which keeps no file modes) is started through the
    // program interpreter its ELF header names. Throws std::runtime_error when the program
    // cannot be started.
    ChildProcess(const std::string& program, const std::vector<std::string>& args);
    // Kills the child if it still runs, and reaps it.
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    int input() const { return input_; }    // -1 once closed
    int output() const { return output_; }  // -1 once closed
    int errors() const { return errors_; }  // -1 once closed
    void closeInput();
    void closeOutput();
    void closeErrors();

    // SIGKILL to the child (nothing once it was reaped).
    void kill();
    // Reaps the child if it has ended: true and its wait status and peak resident memory
    // (bytes); false while it runs.
    bool reaped(int& status, std::uint64_t& peak_rss_bytes);

private:
    pid_t pid_ = -1;
    int input_ = -1, output_ = -1, errors_ = -1;
};

}  // namespace hyvox::os
