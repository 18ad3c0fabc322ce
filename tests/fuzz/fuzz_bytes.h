// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The fuzz input read front to back as plain values: past its end every value reads as zero
// (so any input, however short, decodes to something).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

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

// A soup read from the bytes: `vertex_count` vertices, as raw float32 (NaN, Inf, denormals,
// 1e-37 next to 1e33) when `raw`, else as 16-bit integers in 1/64 steps scaled by a power of
// two from 2^-16 to 2^15 (one byte; exact in float, so alignments with voxel planes occur
// often); then `triangle_count` triangles of one-byte indices taken modulo vertex_count + 1
// (some out of range).
struct Soup {
    std::vector<float> positions;
    std::vector<std::uint32_t> triangles;
};
inline Soup takeSoup(Bytes& bytes, std::size_t vertex_count, std::size_t triangle_count, bool raw) {
    Soup soup;
    soup.positions.resize(3 * vertex_count);
    if (raw) {
        for (float& p : soup.positions) p = bytes.take<float>();
    } else {
        const float scale = std::ldexp(1.0f / 64, int(bytes.take<std::uint8_t>() % 32) - 16);
        for (float& p : soup.positions) p = float(bytes.take<std::int16_t>()) * scale;
    }
    soup.triangles.resize(3 * triangle_count);
    for (std::uint32_t& t : soup.triangles) t = bytes.take<std::uint8_t>() % std::uint32_t(vertex_count + 1);
    return soup;
}

}  // namespace hyvox::fuzz
