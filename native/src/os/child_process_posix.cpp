// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/child_process.h"

#include <elf.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

extern char** environ;

namespace hyvox::os {
namespace {

[[noreturn]] void failSpawn(const std::string& program, const std::string& what, int error) {
    throw std::runtime_error("cannot start " + program + ": " + what + ": " + std::strerror(error));
}

void closeFd(int& fd) {
    if (fd >= 0) ::close(fd);
    fd = -1;
}

// The program interpreter (PT_INTERP) a 64-bit ELF executable names, or "" when it names
// none or the file is not one.
std::string elfInterpreter(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    Elf64_Ehdr header{};
    if (!file.read(reinterpret_cast<char*>(&header), sizeof header) ||
        std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0 || header.e_ident[EI_CLASS] != ELFCLASS64 ||
        header.e_phentsize != sizeof(Elf64_Phdr))
        return "";
    for (int n = 0; n < header.e_phnum; ++n) {
        Elf64_Phdr segment{};
        file.seekg(std::streamoff(header.e_phoff + std::uint64_t(n) * sizeof segment));
        if (!file.read(reinterpret_cast<char*>(&segment), sizeof segment)) return "";
        if (segment.p_type != PT_INTERP) continue;
        if (segment.p_filesz == 0 || segment.p_filesz > 4096) return "";
        std::string interpreter(segment.p_filesz, '\0');
        file.seekg(std::streamoff(segment.p_offset));
        if (!file.read(interpreter.data(), std::streamsize(interpreter.size()))) return "";
        interpreter.resize(std::strlen(interpreter.c_str()));
        return interpreter;
    }
    return "";
}

// posix_spawn's attributes and file actions, destroyed on every path out.
struct SpawnSetup {
    posix_spawnattr_t attributes;
    posix_spawn_file_actions_t actions;
    SpawnSetup() {
        posix_spawnattr_init(&attributes);
        posix_spawn_file_actions_init(&actions);
    }
    ~SpawnSetup() {
        posix_spawn_file_actions_destroy(&actions);
        posix_spawnattr_destroy(&attributes);
    }
};

}  // namespace

ChildProcess::ChildProcess(const std::string& program, const std::vector<std::string>& args) {
    int input[2], output[2], errors[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, input) != 0) failSpawn(program, "socketpair", errno);
    if (::pipe2(output, O_CLOEXEC) != 0) {
        const int error = errno;
        ::close(input[0]);
        ::close(input[1]);
        failSpawn(program, "pipe", error);
    }
    if (::pipe2(errors, O_CLOEXEC) != 0) {
        const int error = errno;
        for (int fd : {input[0], input[1], output[0], output[1]}) ::close(fd);
        failSpawn(program, "pipe", error);
    }
    input_ = input[0];
    output_ = output[0];
    errors_ = errors[0];
    // The child's ends; closed here once it has them (or it failed to start).
    struct Ends {
        int fds[3];
        ~Ends() {
            for (int fd : fds) ::close(fd);
        }
    } ends{{input[1], output[1], errors[1]}};

    SpawnSetup setup;
    sigset_t all, none;
    sigfillset(&all);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&setup.attributes, &all);
    posix_spawnattr_setsigmask(&setup.attributes, &none);
    posix_spawnattr_setpgroup(&setup.attributes, 0);
    posix_spawnattr_setflags(&setup.attributes, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETPGROUP);
    // dup2 clears close-on-exec on the copies; every other descriptor of this process was
    // opened close-on-exec by hyvox, but the host's may not be: closed in the child too.
    posix_spawn_file_actions_adddup2(&setup.actions, input[1], 0);
    posix_spawn_file_actions_adddup2(&setup.actions, output[1], 1);
    posix_spawn_file_actions_adddup2(&setup.actions, errors[1], 2);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 34))
    posix_spawn_file_actions_addclosefrom_np(&setup.actions, 3);
#endif

    std::vector<std::string> argv_strings = args;
    std::string path = program;
    if (::access(program.c_str(), X_OK) != 0) {
        const std::string interpreter = elfInterpreter(program);
        if (interpreter.empty()) {
            closeInput();
            closeOutput();
            closeErrors();
            failSpawn(program, "not executable, and not an ELF program", EACCES);
        }
        argv_strings.insert(argv_strings.begin(), interpreter);
        argv_strings[1] = program;
        path = interpreter;
    }
    std::vector<char*> argv;
    for (std::string& a : argv_strings) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int error = ::posix_spawn(&pid, path.c_str(), &setup.actions, &setup.attributes, argv.data(), environ);
    pid_ = pid;
    if (error != 0) {
        pid_ = -1;
        closeInput();
        closeOutput();
        closeErrors();
        failSpawn(program, "posix_spawn", error);
    }
}

ChildProcess::~ChildProcess() {
    closeInput();
    closeOutput();
    closeErrors();
    if (pid_ > 0) {
        ::kill(pid_t(pid_), SIGKILL);
        int status = 0;
        while (::waitpid(pid_t(pid_), &status, 0) < 0 && errno == EINTR) {}
    }
}

void ChildProcess::closeInput() { closeFd(input_); }
void ChildProcess::closeOutput() { closeFd(output_); }
void ChildProcess::closeErrors() { closeFd(errors_); }

void ChildProcess::exchange(Input& input, const Sink& output, const Sink& errors, int wait_ms) {
    if (input_ >= 0 && input.size == 0) closeInput();
    pollfd fds[3];
    nfds_t n = 0;
    if (output_ >= 0) fds[n++] = {output_, POLLIN, 0};
    if (errors_ >= 0) fds[n++] = {errors_, POLLIN, 0};
    if (input_ >= 0) fds[n++] = {input_, POLLOUT, 0};
    if (n == 0) {
        ::poll(nullptr, 0, wait_ms);  // only the exit to wait for
        return;
    }
    if (::poll(fds, n, wait_ms) <= 0) return;  // timeout or EINTR: the caller looks again
    char buffer[1 << 16];
    for (nfds_t f = 0; f < n; ++f) {
        if (!fds[f].revents) continue;
        const int fd = fds[f].fd;
        if (fd == input_) {
            // MSG_NOSIGNAL: a child that stopped reading is an error code here, not a SIGPIPE.
            const ssize_t sent =
                ::send(fd, input.data, std::min<std::size_t>(input.size, 1 << 20), MSG_NOSIGNAL | MSG_DONTWAIT);
            if (sent > 0) {
                input.data += sent;
                input.size -= std::size_t(sent);
            }
            if (input.size == 0 || (sent < 0 && errno != EAGAIN && errno != EINTR)) closeInput();
            continue;
        }
        const ssize_t got = ::read(fd, buffer, sizeof buffer);
        if (got < 0 && (errno == EAGAIN || errno == EINTR)) continue;
        if (got <= 0) {
            fd == output_ ? closeOutput() : closeErrors();
            continue;
        }
        (fd == output_ ? output : errors)(buffer, std::size_t(got));
    }
}

void ChildProcess::kill() {
    if (pid_ > 0) ::kill(pid_t(pid_), SIGKILL);
}

namespace {
// The name of a signal a child may die of. glibc's sigabbrev_np is 2.32's and newer; the
// release runs on 2.28, and other systems have none.
std::string signalName(int signal) {
    static const std::pair<int, const char*> kNames[] = {
        {SIGHUP, "SIGHUP"},   {SIGINT, "SIGINT"},   {SIGQUIT, "SIGQUIT"}, {SIGILL, "SIGILL"},   {SIGTRAP, "SIGTRAP"},
        {SIGABRT, "SIGABRT"}, {SIGBUS, "SIGBUS"},   {SIGFPE, "SIGFPE"},   {SIGKILL, "SIGKILL"}, {SIGUSR1, "SIGUSR1"},
        {SIGSEGV, "SIGSEGV"}, {SIGUSR2, "SIGUSR2"}, {SIGPIPE, "SIGPIPE"}, {SIGALRM, "SIGALRM"}, {SIGTERM, "SIGTERM"},
        {SIGXCPU, "SIGXCPU"}, {SIGXFSZ, "SIGXFSZ"}, {SIGSYS, "SIGSYS"},
    };
    for (const auto& [number, name] : kNames)
        if (number == signal) return name;
    return "signal " + std::to_string(signal);
}
}  // namespace

std::optional<ChildExit> ChildProcess::reaped() {
    if (pid_ <= 0) return std::nullopt;
    struct rusage usage {};
    int status = 0;
    pid_t got;
    do {
        got = ::wait4(pid_t(pid_), &status, WNOHANG, &usage);
    } while (got < 0 && errno == EINTR);
    if (got != pid_t(pid_)) return std::nullopt;
    pid_ = -1;
    ChildExit exit;
    exit.peak_rss_bytes = std::uint64_t(usage.ru_maxrss) * 1024;  // Linux reports KiB
    if (WIFSIGNALED(status)) {
        exit.signal = signalName(WTERMSIG(status));
    } else if (WIFEXITED(status)) {
        exit.exit_code = WEXITSTATUS(status);
    }
    return exit;
}

std::string ChildProcess::thisProcessId() { return std::to_string(::getpid()); }

}  // namespace hyvox::os
