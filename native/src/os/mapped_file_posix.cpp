// SPDX-License-Identifier: GPL-3.0-or-later
#include "os/mapped_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <mutex>

#include "hyvox/errors.h"
#include "os/file_bytes.h"
#include "os/mesh_file_error.h"

namespace hyvox::os {
namespace {

// The SIGBUS guard: the live mappings (a fixed table, so the handler reads it without locks).
struct GuardSlot {
    std::atomic<std::uintptr_t> begin{0};
    std::atomic<std::size_t> size{0};
    std::atomic<bool> faulted{false};
};
constexpr int kSlots = 16;
GuardSlot g_slots[kSlots];
struct sigaction g_previous;

void onSigbus(int signal, siginfo_t* info, void* context) {
    const auto address = reinterpret_cast<std::uintptr_t>(info->si_addr);
    for (GuardSlot& slot : g_slots) {
        const std::uintptr_t begin = slot.begin.load();
        if (begin <= 1 || address < begin || address >= begin + slot.size.load()) continue;
        // Ours: a page of zeros over the missing one; the faulting load then reads zeros.
        const auto page_size = std::uintptr_t(sysconf(_SC_PAGESIZE));
        void* page = reinterpret_cast<void*>(address & ~(page_size - 1));
        if (mmap(page, page_size, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) != MAP_FAILED) {
            slot.faulted.store(true);
            return;
        }
        break;
    }
    // Not ours: whatever handled SIGBUS before (the default ends the process, as without us).
    if (g_previous.sa_flags & SA_SIGINFO) {
        if (g_previous.sa_sigaction) return g_previous.sa_sigaction(signal, info, context);
    } else if (g_previous.sa_handler != SIG_DFL && g_previous.sa_handler != SIG_IGN && g_previous.sa_handler) {
        return g_previous.sa_handler(signal);
    }
    sigaction(SIGBUS, &g_previous, nullptr);  // returning re-runs the load, now under it
}

void installGuard() {
    static std::once_flag once;
    std::call_once(once, [] {
        struct sigaction action {};
        action.sa_sigaction = onSigbus;
        action.sa_flags = SA_SIGINFO | SA_NODEFER;
        sigemptyset(&action.sa_mask);
        sigaction(SIGBUS, &action, &g_previous);
    });
}

// A free slot for [data, data + size), or -1. The slot is taken (begin = 1, never a mapped
// address) before its size is written, so the handler never pairs one mapping's start with
// another's size.
int claimSlot(const char* data, std::size_t size) {
    for (int i = 0; i < kSlots; ++i) {
        std::uintptr_t expected = 0;
        if (!g_slots[i].begin.compare_exchange_strong(expected, 1)) continue;
        g_slots[i].size.store(size);
        g_slots[i].faulted.store(false);
        g_slots[i].begin.store(reinterpret_cast<std::uintptr_t>(data));
        return i;
    }
    return -1;
}

struct Fd {
    int fd;
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

MappedFile::MappedFile(const std::string& path, std::size_t max_bytes) {
    // O_NONBLOCK: opening a FIFO with no writer must not hang; it is refused just after.
    const Fd file{::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
    struct stat st {};
    if (file.fd < 0 || ::fstat(file.fd, &st) != 0)
        throw InvalidInput("cannot open mesh file '" + path + "': " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw InvalidInput("mesh path '" + path + "' is a folder, not a file");
    if (!S_ISREG(st.st_mode))
        throw InvalidInput("mesh path '" + path + "' is not a regular file (a device, FIFO or socket is not read)");
    if (std::uint64_t(st.st_size) > max_bytes)
        failMeshFile(path,
                     "is " + std::to_string(st.st_size) + " bytes, more than the " + std::to_string(max_bytes) +
                         " this reader accepts");
    size_ = std::size_t(st.st_size);
    if (size_ == 0) return;
    installGuard();
    void* p = mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, file.fd, 0);
    if (p == MAP_FAILED) throw InvalidInput("cannot read mesh file '" + path + "': " + std::strerror(errno));
    data_ = static_cast<const char*>(p);
    slot_ = claimSlot(data_, size_);
    if (slot_ < 0) {  // more files mapped at once than the guard holds: this one is read
        munmap(p, size_);
        copy_ = readFileBytes(path, max_bytes);
        data_ = copy_.data();
        size_ = copy_.size();
    }
}

MappedFile::~MappedFile() {
    if (slot_ < 0) return;
    munmap(const_cast<char*>(data_), size_);
    g_slots[slot_].begin.store(0);
}

bool MappedFile::changedWhileRead() const { return slot_ >= 0 && g_slots[slot_].faulted.load(); }

}  // namespace hyvox::os
