// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/mesh_wire.h"

#include <algorithm>
#include <cstring>
#include <limits>

namespace hyvox::mesh_io::wire {
namespace {

constexpr std::uint8_t kColors = 1, kAlpha = 2, kUvs = 4;
constexpr std::size_t kHeaderBytes = 8 + 8 + 1 + 4;
// A warning is a sentence; more than this is no reader's.
constexpr std::uint32_t kMaxTextBytes = 1 << 16;
constexpr std::uint32_t kMaxWarnings = 64;

template <typename T>
void put(std::string& out, T value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

void putText(std::string& out, const std::string& text) {
    const std::string cut = text.substr(0, kMaxTextBytes);
    put(out, std::uint32_t(cut.size()));
    out += cut;
}

template <typename T>
void putArray(std::string& out, const std::vector<T>& values) {
    out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

template <typename T>
T get(const char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return value;
}

}  // namespace

std::string progressMessage(int percent) {
    std::string out = "P";
    put(out, std::uint8_t(std::clamp(percent, 0, 100)));
    return out;
}

std::string errorMessage(const std::string& what) {
    std::string out = "E";
    putText(out, what);
    return out;
}

std::string meshMessage(const Mesh& mesh) {
    std::string out = "M";
    const std::uint8_t flags =
        std::uint8_t((mesh.hasColors() ? kColors : 0) | (mesh.colors_alpha ? kAlpha : 0) | (mesh.hasUvs() ? kUvs : 0));
    put(out, std::uint64_t(mesh.vertexCount()));
    put(out, std::uint64_t(mesh.triangleCount()));
    put(out, flags);
    const std::size_t warnings = std::min<std::size_t>(mesh.warnings.size(), kMaxWarnings);
    put(out, std::uint32_t(warnings));
    for (std::size_t w = 0; w < warnings; ++w) putText(out, mesh.warnings[w]);
    putArray(out, mesh.positions);
    putArray(out, mesh.triangles);
    putArray(out, mesh.colors);
    putArray(out, mesh.uvs);
    return out;
}

bool Decoder::take(char* into, std::size_t want, const char*& data, std::size_t& size) {
    const std::size_t n = std::min(want - have_, size);
    if (n) std::memcpy(into + have_, data, n);
    have_ += n;
    data += n;
    size -= n;
    if (have_ < want) return false;
    have_ = 0;
    return true;
}

void Decoder::startArrays() {
    // Sizes in doubles first: 2^64 vertices must not wrap into a small product.
    const bool colors = flags_ & kColors, uvs = flags_ & kUvs;
    const double bytes =
        double(vertices_) * (12.0 + (colors ? 16.0 : 0.0) + (uvs ? 8.0 : 0.0)) + double(triangles_) * 12.0;
    check(bytes + double(accepted_bytes_) <= double(max_mesh_bytes_), "a mesh larger than the memory budget");
    check(vertices_ <= std::numeric_limits<std::uint32_t>::max(), "more vertices than 32-bit indices can name");
    check(vertices_ > 0 && triangles_ > 0, "a mesh without triangles");
    mesh_.positions.resize(3 * vertices_);
    mesh_.triangles.resize(3 * triangles_);
    arrays_[array_count_++] = {reinterpret_cast<char*>(mesh_.positions.data()), mesh_.positions.size() * sizeof(float)};
    arrays_[array_count_++] = {reinterpret_cast<char*>(mesh_.triangles.data()),
                               mesh_.triangles.size() * sizeof(std::uint32_t)};
    if (colors) {
        mesh_.colors.resize(4 * vertices_);
        mesh_.colors_alpha = flags_ & kAlpha;
        arrays_[array_count_++] = {reinterpret_cast<char*>(mesh_.colors.data()), mesh_.colors.size() * sizeof(float)};
    }
    if (uvs) {
        mesh_.uvs.resize(2 * vertices_);
        arrays_[array_count_++] = {reinterpret_cast<char*>(mesh_.uvs.data()), mesh_.uvs.size() * sizeof(float)};
    }
    state_ = State::Arrays;
}

void Decoder::feed(const char* data, std::size_t size) {
    while (size > 0) {
        switch (state_) {
            case State::Tag: {
                const char tag = *data++;
                --size;
                if (tag == 'P')
                    state_ = State::Percent;
                else if (tag == 'E')
                    state_ = State::ErrorSize;
                else if (tag == 'M')
                    state_ = State::Header;
                else
                    throw StreamError{"a message of no known kind"};
                break;
            }
            case State::Percent:
                percent_ = std::min(100, int(std::uint8_t(*data++)));
                --size;
                state_ = State::Tag;
                break;
            case State::ErrorSize:
            case State::WarningSize:
                if (take(scratch_, 4, data, size)) {
                    const std::uint32_t n = get<std::uint32_t>(scratch_);
                    check(n <= kMaxTextBytes, "a message longer than any reader writes");
                    text_.assign(n, '\0');
                    state_ = state_ == State::ErrorSize ? State::ErrorText : State::WarningText;
                }
                break;
            case State::ErrorText:
            case State::WarningText: break;  // below, where an empty text completes at once too
            case State::Header:
                if (take(scratch_, kHeaderBytes, data, size)) {
                    vertices_ = get<std::uint64_t>(scratch_);
                    triangles_ = get<std::uint64_t>(scratch_ + 8);
                    flags_ = get<std::uint8_t>(scratch_ + 16);
                    warnings_left_ = get<std::uint32_t>(scratch_ + 17);
                    check((flags_ & ~(kColors | kAlpha | kUvs)) == 0 && (!(flags_ & kAlpha) || (flags_ & kColors)),
                          "a mesh with unknown attributes");
                    check(warnings_left_ <= kMaxWarnings, "more warnings than any reader writes");
                    if (warnings_left_ > 0)
                        state_ = State::WarningSize;
                    else
                        startArrays();
                }
                break;
            case State::Arrays:
                if (take(arrays_[array_].data, arrays_[array_].bytes, data, size)) {
                    ++array_;
                    if (array_ == array_count_) state_ = State::Done;
                }
                break;
            case State::Done: throw StreamError{"bytes after the mesh"};
        }
        // A text is copied straight into its string; it completes when all of it is there.
        if (state_ == State::ErrorText || state_ == State::WarningText) {
            if (!take(text_.data(), text_.size(), data, size)) continue;
            accepted_bytes_ += text_.size();
            if (state_ == State::ErrorText) {
                error_ = std::move(text_);
                state_ = State::Done;
            } else {
                mesh_.warnings.push_back(std::move(text_));
                if (--warnings_left_ > 0)
                    state_ = State::WarningSize;
                else
                    startArrays();
            }
            text_.clear();
        }
    }
}

Mesh Decoder::finish() {
    check(state_ == State::Done, "the stream ended before a whole mesh or error");
    check(!error_, "an error, not a mesh");
    const std::uint64_t n = vertices_;
    for (std::uint32_t index : mesh_.triangles) check(index < n, "a triangle index past the vertices");
    return std::move(mesh_);
}

}  // namespace hyvox::mesh_io::wire
