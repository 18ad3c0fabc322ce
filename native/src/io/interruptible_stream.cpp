// SPDX-License-Identifier: GPL-3.0-or-later
#include "io/interruptible_stream.h"

#include <algorithm>

namespace hyvox::io {

InterruptibleStreamBuf::InterruptibleStreamBuf(std::streambuf* target, Interrupter* interrupter,
                                               std::uint64_t expected_bytes, int first_percent, int last_percent,
                                               std::uint64_t check_bytes)
    : target_(target),
      interrupter_(interrupter),
      expected_(std::max<std::uint64_t>(expected_bytes, 1)),
      first_(first_percent),
      last_(last_percent),
      check_bytes_(std::max<std::uint64_t>(check_bytes, 1)),
      next_check_(check_bytes_) {}

void InterruptibleStreamBuf::wrote(std::uint64_t bytes) {
    written_ += bytes;
    if (!interrupter_ || written_ < next_check_) return;
    next_check_ = written_ + check_bytes_;
    // The expected size is an estimate: the percent stops short of last_ until the end.
    const std::uint64_t span = std::uint64_t(last_ - first_);
    const int percent = first_ + int(std::min<std::uint64_t>(span * written_ / expected_, span > 0 ? span - 1 : 0));
    throwIfInterrupted(interrupter_, percent);
}

InterruptibleStreamBuf::int_type InterruptibleStreamBuf::overflow(int_type c) {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    if (traits_type::eq_int_type(target_->sputc(traits_type::to_char_type(c)), traits_type::eof()))
        return traits_type::eof();
    wrote(1);
    return c;
}

std::streamsize InterruptibleStreamBuf::xsputn(const char* s, std::streamsize n) {
    const std::streamsize done = target_->sputn(s, n);
    if (done > 0) wrote(std::uint64_t(done));
    return done;
}

int InterruptibleStreamBuf::sync() { return target_->pubsync(); }

InterruptibleStreamBuf::pos_type InterruptibleStreamBuf::seekoff(off_type off, std::ios_base::seekdir dir,
                                                                 std::ios_base::openmode which) {
    return target_->pubseekoff(off, dir, which);
}

InterruptibleStreamBuf::pos_type InterruptibleStreamBuf::seekpos(pos_type pos, std::ios_base::openmode which) {
    return target_->pubseekpos(pos, which);
}

}  // namespace hyvox::io
