// SPDX-License-Identifier: GPL-3.0-or-later
#include "hyvox/attribute_grid.h"

#include "hyvox/errors.h"

namespace hyvox {

AttributeSet parseAttributeSet(const std::string& text) {
    AttributeSet set;
    std::size_t begin = 0;
    while (begin < text.size()) {
        const std::size_t comma = std::min(text.find(',', begin), text.size());
        const std::string name = text.substr(begin, comma - begin);
        if (name == "color")
            set.color = true;
        else if (name == "normal")
            set.normal = true;
        else
            throw InvalidInput("attributes: unknown attribute '" + name + "' in '" + text +
                               "' (a comma list of: color, normal)");
        begin = comma + 1;
    }
    return set;
}

}  // namespace hyvox
