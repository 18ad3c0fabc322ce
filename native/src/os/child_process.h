// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A helper program run beside this process, for work that must not be able to end it (the
// assimp reader: mesh_io/assimp_reader.h). Nothing of this process is copied into it: the
// caller may be Blender or a Python process with GL contexts and TBB threads, where a copy
// could deadlock on a lock another thread held (child_process_posix.cpp: posix_spawn, never
// fork).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace hyvox::os {

// How a child process ended.
struct ChildExit {
    int exit_code = -1;                // its exit status; -1 when a signal ended it
    std::string signal;                // the signal that ended it ("SIGSEGV"), "" when it exited
    std::uint64_t peak_rss_bytes = 0;  // its peak resident memory
};

class ChildProcess {
public:
    // Starts `program` with `args` (args[0] is the name it is given). Its standard input is a
    // socket this process writes (a child that died is an error code, never a SIGPIPE here),
    // its standard output and error are pipes this process reads; no other descriptor is
    // passed on. Every signal is at its default and unblocked in the child, which runs in a
    // process group of its own (a Ctrl-C at the terminal reaches this process only, which
    // then ends the child). A program file without its execute bit (unpacked from a zip,
    // which keeps no file modes) is started through the program interpreter its ELF header
    // names. Throws std::runtime_error when the program cannot be started.
    ChildProcess(const std::string& program, const std::vector<std::string>& args);
    // Kills the child if it still runs, and reaps it.
    ~ChildProcess();
    ChildProcess(const ChildProcess&) = delete;
    ChildProcess& operator=(const ChildProcess&) = delete;

    // What is left to send to the child's standard input (advanced as the child takes it).
    struct Input {
        const char* data = nullptr;
        std::size_t size = 0;
    };
    // Bytes the child wrote, handed over as they come.
    using Sink = std::function<void(const char* bytes, std::size_t size)>;
    // One step of the exchange with the child: waits up to `wait_ms` for its standard input,
    // output and error, sends it what it takes of `input` (its standard input is closed once
    // all is sent, or when the child stopped reading: it ended, and its exit says why), and
    // hands what it wrote to `output` and `errors`. With all three closed it just waits (the
    // caller waits for the exit).
    void exchange(Input& input, const Sink& output, const Sink& errors, int wait_ms);
    // Whether its standard output or error is still open (it may still write).
    bool writing() const { return output_ >= 0 || errors_ >= 0; }

    // Kills the child (nothing once it was reaped).
    void kill();
    // Reaps the child if it has ended: how it ended; nothing while it runs.
    std::optional<ChildExit> reaped();

    // This process's id as the child's arguments give it (for a child that ends itself
    // once its parent is gone).
    static std::string thisProcessId();

private:
    void closeInput();
    void closeOutput();
    void closeErrors();

    long pid_ = -1;                               // -1: not started, or reaped
    int input_ = -1, output_ = -1, errors_ = -1;  // the ends of this process, -1 once closed
};

}  // namespace hyvox::os
