// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// A stream buffer in front of another that asks an Interrupter as the bytes go by, so that
// a long write (OpenVDB serialising a large grid, which has no interrupter of its own) can
// be cancelled and followed: every `check_bytes` it reports progress between first and last
// percent (by the bytes written of those expected) and throws hyvox::Cancelled when asked
// to stop. With badbit in the stream's exception mask the Cancelled reaches the caller.
// Seeks go through unchanged (OpenVDB seeks back to fill in grid offsets); nothing is
// buffered here, so positions stay the target's.
#include <cstdint>
#include <streambuf>

#include "hyvox/interrupter.h"

namespace hyvox::io {

class InterruptibleStreamBuf final : public std::streambuf {
public:
    InterruptibleStreamBuf(std::streambuf* target, Interrupter* interrupter, std::uint64_t expected_bytes,
                           int first_percent, int last_percent, std::uint64_t check_bytes = 256 * 1024);

protected:
    int_type overflow(int_type c) override;
    std::streamsize xsputn(const char* s, std::streamsize n) override;
    int sync() override;
    pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode which) override;
    pos_type seekpos(pos_type pos, std::ios_base::openmode which) override;

private:
    void wrote(std::uint64_t bytes);

    std::streambuf* target_;
    Interrupter* interrupter_;
    std::uint64_t expected_;
    int first_, last_;
    std::uint64_t check_bytes_;
    std::uint64_t written_ = 0;
    std::uint64_t next_check_;
};

}  // namespace hyvox::io
