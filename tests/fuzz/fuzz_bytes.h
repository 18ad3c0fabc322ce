// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The fuzz input read front to back as plain values: past its end every value reads as zero
// (so any input, however short, decodes to something).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hyvox::fuzz {

class Bytes {
public:
    Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
    template <typename T>
    T take() {
        T value{};
        const std::size_t n = std::min(sizeof(T), size_ - std::min(size_, at_));
        if (n) std::memcpy(&value, data_ + at_, n);
        at_ += sizeof(T);
        return value;
    }

private:
    const std::uint8_t* data_;
    std::size_t size_, at_ = 0;
};

}  // namespace hyvox::fuzz
