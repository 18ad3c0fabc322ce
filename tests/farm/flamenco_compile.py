# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs a Flamenco job type's compileJob in QuickJS against flamenco_api.js:

python flamenco_compile.py JOB_TYPE.js SETTINGS_JSON    prints {"jobType", "tasks"} as JSON
python flamenco_compile.py JOB_TYPE.js                  prints JOB_TYPE as JSON"""

import os
import sys

import quickjs


def main(job_type, settings=None):
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "flamenco_api.js")) as f:
        api = f.read()
    with open(job_type) as f:
        source = f.read()
    context = quickjs.Context()
    context.eval(api + "\n" + source)
    print(context.get("hyvoxCompile")(settings) if settings is not None else context.get("hyvoxJobType")())


if __name__ == "__main__":
    main(*sys.argv[1:])
