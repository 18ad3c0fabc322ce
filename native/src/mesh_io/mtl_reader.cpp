// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_io/mtl_reader.h"

#include <algorithm>
#include <cmath>

#include "hyvox/errors.h"
#include "mesh_io/text_scanner.h"

namespace hyvox::mesh_io {
namespace {

// The rest of the current line without its surrounding blanks ("" at the end of a line).
std::string_view restOfLine(TextScanner& scanner) {
    std::string_view first;
    if (!scanner.wordOnLine(first)) return {};
    const char* from = first.data();
    const char* to = first.data() + first.size();
    std::string_view word;
    while (scanner.wordOnLine(word)) to = word.data() + word.size();
    return std::string_view(from, std::size_t(to - from));
}

// map_Kd's file: after any "-option values" the exporter wrote, the line's last word; with no
// options, the whole rest of the line (Blender writes names with blanks as they are).
std::string mapFile(std::string_view rest) {
    if (rest.empty() || rest.front() != '-') return std::string(rest);
    const std::size_t blank = rest.find_last_of(" \t");
    return std::string(blank == std::string_view::npos ? rest : rest.substr(blank + 1));
}

}  // namespace

std::vector<MtlMaterial> readMtl(const char* data, std::size_t size, const std::string& name) {
    TextScanner scanner(data, data + size);
    std::vector<MtlMaterial> materials;
    auto fail = [&](const std::string& what) {
        throw InvalidInput("material file '" + name + "': line " + std::to_string(scanner.line()) + ": " + what);
    };
    auto current = [&](std::string_view keyword) -> MtlMaterial& {
        if (materials.empty()) fail("'" + std::string(keyword) + "' comes before any 'newmtl'");
        return materials.back();
    };
    do {
        std::string_view keyword;
        if (!scanner.wordOnLine(keyword)) continue;
        if (keyword == "newmtl") {
            const std::string_view material = restOfLine(scanner);
            if (material.empty()) fail("'newmtl' needs a material name");
            materials.push_back({std::string(material), std::nullopt, ""});
        } else if (keyword == "Kd") {
            MtlMaterial& m = current(keyword);
            float values[3];
            int n = 0;
            std::string_view word;
            while (scanner.wordOnLine(word)) {
                if (n == 3) fail("'Kd' has r g b (or one grey value), this one more than 3 numbers");
                if (!parseNumber(word, values[n]) || !std::isfinite(values[n]))
                    fail(quoteWord(word) + " is not a number ('Kd spectral' and 'Kd xyz' are not read)");
                ++n;
            }
            if (n != 1 && n != 3)
                fail("'Kd' has r g b (or one grey value), this one " + std::to_string(n) + " numbers");
            m.diffuse = std::array<float, 3>{values[0], values[n == 3 ? 1 : 0], values[n == 3 ? 2 : 0]};
        } else if (keyword == "map_Kd") {
            MtlMaterial& m = current(keyword);
            m.diffuse_map = mapFile(restOfLine(scanner));
            if (m.diffuse_map.empty()) fail("'map_Kd' needs a file name");
            std::replace(m.diffuse_map.begin(), m.diffuse_map.end(), '\\', '/');
        }
    } while (scanner.nextLine());
    return materials;
}

}  // namespace hyvox::mesh_io
