#!/usr/bin/env python3
"""Where a controller's missed frames come from, from a `steadyray bench` frames.csv.

For each controller: the share of frames in the band, reversals per 100 frames, frames over
and under the band, and the cuts made right after a frame over Tmax, by where the next frame
landed (under, in or over the band) and how many of them followed a single frame over (the
frame before it in or under the band: a spike's cut). A cut that lands under the band after
one slow frame is a controller that believed a spike.

    python3 scripts/misses.py results/bench/frames.csv [--band 15 20]
"""

import argparse
import csv
from collections import defaultdict


def work(row):
    """Nominal work of a row's quality: S x scale^2 x (R + 1)."""
    return float(row["spp"]) * float(row["scale"]) ** 2 * (int(row["depth"]) + 1)


def reversals(levels):
    """Quality changes whose direction is opposite to the previous change's."""
    count, last = 0, 0
    for before, after in zip(levels, levels[1:]):
        if after == before:
            continue
        direction = 1 if after > before else -1
        if last and direction != last:
            count += 1
        last = direction
    return count


def misses(rows, tmin, tmax):
    """The figures of one controller's rows (in frame order)."""
    tp = [float(r["tp_ms"]) for r in rows]
    levels = [work(r) for r in rows]
    landed = {"under": 0, "in": 0, "over": 0}
    after_single = 0
    for i in range(len(tp) - 1):
        if tp[i] > tmax and levels[i + 1] < levels[i]:
            nxt = tp[i + 1]
            landed["under" if nxt < tmin else "in" if nxt <= tmax else "over"] += 1
            if i > 0 and tp[i - 1] <= tmax:
                after_single += 1
    n = len(tp)
    return {
        "frames": n,
        "in_band_pct": round(100 * sum(tmin <= t <= tmax for t in tp) / n, 1),
        "reversals_per_100": round(100 * reversals(levels) / n, 2),
        "over": sum(t > tmax for t in tp),
        "under": sum(t < tmin for t in tp),
        "cuts_after_over": sum(landed.values()),
        "cut_landed": landed,
        "cuts_after_one_slow_frame": after_single,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("frames_csv")
    parser.add_argument("--band", nargs=2, type=float, default=[15.0, 20.0])
    args = parser.parse_args()
    by_controller = defaultdict(list)
    with open(args.frames_csv, newline="") as f:
        for row in csv.DictReader(f):
            by_controller[row["controller"]].append(row)
    for name, rows in by_controller.items():
        print(name, misses(rows, *args.band))


if __name__ == "__main__":
    main()
