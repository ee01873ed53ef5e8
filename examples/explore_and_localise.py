#!/usr/bin/env python3
"""Explore a rendered route into a map, localise query views, plot where they were placed.

A ground-truth experiment with omninav's Python module: the renderer gives panoramas with
exact poses, the map is made from the route's panoramas alone, and the queries, taken at poses
of their own near the route, are localised coarse to fine. The figure shows the route, its
places, and each query joined to the place it was localised at (green: within 0.3 m).

    export PYTHONPATH=$PWD/build/python
    python3 examples/explore_and_localise.py --out localisation.png
"""

import argparse
import math

import matplotlib.pyplot as plt  # without a display (or with MPLBACKEND=Agg): to a file only

import omninav


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--world", default="room:seed=6,boxes=6", help="a world of worlds.yaml")
    parser.add_argument("--route", default="wander:length_m=12,seed=2",
                        help="the route, as `omninav render --trajectory` takes it")
    parser.add_argument("--queries", type=int, default=12, help="query views to localise")
    parser.add_argument("--width", type=int, default=360, help="panorama width, pixels")
    parser.add_argument("--height", type=int, default=45, help="panorama height, pixels")
    parser.add_argument("--out", default="localisation.png", help="the figure (PNG)")
    args = parser.parse_args()

    world = omninav.World(args.world, width_px=args.width, height_px=args.height)
    renderer = omninav.Renderer(world)

    # Explore: the route's panoramas become places where the view changes enough.
    route = world.trajectory(args.route)
    frames = (omninav.Frame(renderer.render(pose, time_s), index=i, truth=pose, time_s=time_s)
              for i, (time_s, pose) in enumerate(route))
    memory = omninav.Map()
    run = memory.explore(frames)
    places = memory.places()
    print(f"explored {run.frames} frames of {world.name}: {memory.place_count} places, "
          f"{memory.edge_count} edges, headings from the {run.heading_source}")

    # Localise: views beside the route, turned every which way.
    localiser = omninav.Localiser(memory)
    step = max(1, len(route) // args.queries)
    results = []
    for k, (_, pose) in enumerate(route[step // 2::step]):
        query = omninav.CameraPose(pose.x_m + 0.1 * math.cos(k), pose.y_m + 0.1 * math.sin(k),
                                   pose.z_m, heading_rad=pose.heading_rad + 1.3 * k)
        best = localiser.localise(renderer.render(query)).best[0]
        place = places[best.place].truth
        error_m = math.hypot(place.x_m - query.x_m, place.y_m - query.y_m)
        results.append((query, place, error_m))
        print(f"query at ({query.x_m:.2f}, {query.y_m:.2f}) m: place {best.place}, "
              f"{error_m:.2f} m away, similarity {best.similarity:.0f}")

    figure, axes = plt.subplots(figsize=(7, 5))
    axes.plot([p.x_m for _, p in route], [p.y_m for _, p in route], color="0.7", label="route")
    axes.scatter([p.truth.x_m for p in places], [p.truth.y_m for p in places], s=20,
                 color="tab:blue", label="places", zorder=3)
    for index, (query, place, error_m) in enumerate(results):
        colour = "tab:green" if error_m < 0.3 else "tab:red"
        axes.plot([query.x_m, place.x_m], [query.y_m, place.y_m], color=colour, linewidth=2)
        axes.scatter([query.x_m], [query.y_m], marker="x", color=colour, zorder=4,
                     label="query, joined to its best place" if index == 0 else None)
    axes.set_aspect("equal")
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    near = sum(error_m < 0.3 for _, _, error_m in results)
    axes.set_title(f"{near} of {len(results)} queries localised within 0.3 m")
    axes.legend(loc="best")
    figure.savefig(args.out, dpi=100, bbox_inches="tight")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
