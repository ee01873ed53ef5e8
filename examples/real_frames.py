#!/usr/bin/env python3
"""Real panoramas to a map, localisation and a plot: docs/tutorial.md, in Python.

A folder of real, already unwrapped panoramas taken one after the other along a route (the
arena frames of ../shared/data/real/ftl-arena/route: no poses were recorded). Every other frame
goes into the map; the frames in between are localised against it. With no ground-truth
poses, the order of the frames is the truth: a query lies between the places explored just
before and just after it along the route, so its best place should be one of those two. The compass integrates the heading along the whole route. The figure shows both.

    export PYTHONPATH=$PWD/build/python
    python3 examples/real_frames.py ../shared/data/real/ftl-arena/route --out arena.png
"""

import argparse
import math

import matplotlib.pyplot as plt  # without a display (or with MPLBACKEND=Agg): to a file only

import omninav


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("frames", help="a folder of panoramas in the order they were taken")
    parser.add_argument("--out", default="arena.png", help="the figure (PNG)")
    args = parser.parse_args()

    frames = list(omninav.open_sequence(args.frames))
    height, width = frames[0].image.shape[:2]
    print(f"{len(frames)} panoramas of {width} x {height} pixels")

    # The map: the even frames, a place wherever the view has changed enough (memory.yaml).
    memory = omninav.Map()
    run = memory.explore(frames[::2])
    place_frame = [place.frame_index for place in memory.places()]  # the frames keep their index
    print(f"explored {run.frames} frames: {memory.place_count} places")

    # Localise the odd frames. How far in time from the query was the best place's frame?
    localiser = omninav.Localiser(memory)
    queries, best_frames = [], []
    for index in range(1, len(frames), 2):
        best = localiser.localise(frames[index].image).best[0]
        queries.append(index)
        best_frames.append(place_frame[best.place])
    # The places explored just before and just after each query bracket it along the route:
    # either is right.
    before = [max((f for f in place_frame if f < q), default=None) for q in queries]
    after = [min((f for f in place_frame if f > q), default=None) for q in queries]
    right = sum(b in (lo, hi) for b, lo, hi in zip(best_frames, before, after))
    print(f"localised {len(queries)} queries: {right} at a place explored just before or after "
          f"them ({100 * right / len(queries):.0f} %)")

    # The compass along the whole route, every frame.
    compass = omninav.Compass()
    headings = [math.degrees(compass.push(frame.image).heading_rad) for frame in frames]
    print(f"compass: {headings[-1]:.1f} deg at the last frame, relative to the first")

    figure, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    left.fill_between(queries, [b if b is not None else q for b, q in zip(before, queries)],
                      [a if a is not None else q for a, q in zip(after, queries)], color="0.85",
                      step="mid", label="places just before and after")
    left.scatter(queries, best_frames, s=12, color="tab:blue", label="best place")
    left.set(xlabel="query frame", ylabel="frame of the best place",
             title="Localisation of the odd frames")
    left.legend()
    right.plot(range(len(frames)), headings, color="tab:red")
    right.set(xlabel="frame", ylabel="heading (deg)", title="Visual compass along the route")
    figure.tight_layout()
    figure.savefig(args.out, dpi=100)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
