// SPDX-License-Identifier: GPL-3.0-or-later
#include "farm/flamenco_job_type.h"

namespace hyvox::farm {

std::string flamencoJobType() { return "TODO\n"; }

}  // namespace hyvox::farm
