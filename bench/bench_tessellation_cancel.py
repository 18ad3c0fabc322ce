# SPDX-License-Identifier: GPL-3.0-or-later
"""Benchmark (not a test): how soon a cancel stops the tessellation method.

    PYTHONPATH=build/python python3 bench/bench_tessellation_cancel.py [--res 4096] [--gamma 4] [--after 1] [--out DIR]

A 12-triangle box at --res with tess_gamma --gamma (about 12 * (gamma * res)^2 points: 3.2e9
at the defaults, about a minute on llvmpipe) is cancelled from another thread --after seconds;
prints how long hyvox.Cancelled took to arrive after token.cancel(), and writes it to
DIR/tessellation_cancel.{json,md} (default bench/results/)."""

import argparse
import threading
import time

import numpy as np

import hyvox
from bench_results import Column, Table, add_out_argument

BOX_V = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]], np.float32)
BOX_T = np.array(
    [
        [0, 2, 1],
        [0, 3, 2],
        [4, 5, 6],
        [4, 6, 7],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ],
    np.uint32,
)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--res", type=int, default=4096)
    parser.add_argument("--gamma", type=float, default=4.0)
    parser.add_argument("--after", type=float, default=1.0)
    add_out_argument(parser)
    args = parser.parse_args()
    table = Table(
        "tessellation_cancel",
        "How soon a cancel stops the tessellation method",
        [
            Column("box at res"),
            Column("γ"),
            Column("cancelled after s", 1),
            Column("finished"),
            Column("Cancelled arrived after s", 3),
        ],
        extra_machine={"gpu": "EGL: " + ", ".join(d.name for d in hyvox.gl_devices())},
    )
    token = hyvox.CancelToken()
    cancelled_at = []

    def cancel_later():
        time.sleep(args.after)
        cancelled_at.append(time.perf_counter())
        token.cancel()

    threading.Thread(target=cancel_later, daemon=True).start()
    start = time.perf_counter()
    try:
        hyvox.voxelize(
            BOX_V,
            BOX_T,
            resolution=args.res,
            method="tessellation",
            tess_gamma=args.gamma,
            tess_counts=False,
            cancel=token,
            memory_budget_mib=8192,
        )
        print(f"finished in {time.perf_counter() - start:.2f} s before the cancel")
        table.add([args.res, args.gamma, args.after, "before the cancel", None])
    except hyvox.Cancelled:
        late = time.perf_counter() - cancelled_at[0]
        print(
            f"hyvox.Cancelled {late:.3f} s after token.cancel() "
            f"(box at {args.res}, gamma {args.gamma}, cancelled after {args.after} s)"
        )
        table.add([args.res, args.gamma, args.after, "no", late])
    table.write(args.out)


if __name__ == "__main__":
    main()
