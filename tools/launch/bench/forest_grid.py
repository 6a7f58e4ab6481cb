#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The forest benchmark's grid (forest_bench.sh): reads the campaign's JSON (runs swept over
world:forest.density, control:follower.max_speed and world:forest.seed), prints the grid, and
writes grid.json and grid.svg next to it (success rate and average speed reached against the
commanded speed, a line a density).

    forest_grid.py CAMPAIGN_JSON
"""
import json
import os
import statistics
import sys

DENSITY = "world:forest.density"
SPEED = "control:follower.max_speed"


def median(runs, key):
    values = [r[key] for r in runs if r.get(key) is not None]
    return statistics.median(values) if values else None


def m2_per_tree(density):
    """Trees per m^2 (the axis's value) as square metres per tree, as the paper gives it."""
    return round(1.0 / float(density))


def cell(runs, density, speed):
    ok = [r for r in runs if r.get("success")]
    clearances = [r["min_clearance_m"] for r in runs if r.get("min_clearance_m") is not None]
    return {
        "m2_per_tree": m2_per_tree(density),
        "speed_mps": float(speed),
        "runs": len(runs),
        "successes": len(ok),
        "collisions": sum(r.get("collisions", 0) for r in runs),
        "average_speed_mps": median(ok, "average_speed_mps"),
        "top_speed_mps": median(ok, "top_speed_mps"),
        "time_to_goal_s": median(ok, "time_to_goal_s"),
        "flown_over_optimum": median(ok, "flown_over_optimum"),
        "closest_approach_m": min(clearances) if clearances else None,
        "depth_to_command_max_s": max((r["depth_to_command_max_s"] for r in runs
                                       if r.get("depth_to_command_max_s") is not None), default=None),
        "estimate_rms_m": median(runs, "estimate_rms_m"),
        "estimate_nees": median(runs, "estimate_nees"),
    }


def svg(grid, densities, speeds):
    """Two panels side by side: success rate and average speed against the commanded speed."""
    w, h, pad = 300, 220, 40
    vmax = max(float(s) for s in speeds)
    colours = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a"]
    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{2 * w + 3 * pad}" height="{h + 2 * pad}" '
             'font-family="sans-serif" font-size="11">']
    panels = [("success rate", lambda c: c["successes"] / c["runs"] if c["runs"] else None, 1.0),
              ("average speed reached [m/s]", lambda c: c["average_speed_mps"], vmax)]
    for i, (title, value, ymax) in enumerate(panels):
        x0 = pad + i * (w + pad)
        x = lambda v: x0 + w * float(v) / vmax
        y = lambda v: pad + h - h * v / ymax
        parts.append(f'<text x="{x0}" y="{pad - 12}">{title}</text>')
        parts.append(f'<rect x="{x0}" y="{pad}" width="{w}" height="{h}" fill="none" stroke="#888"/>')
        for s in speeds:
            parts.append(f'<text x="{x(s) - 4}" y="{pad + h + 14}">{s}</text>')
        parts.append(f'<text x="{x0 + w / 2 - 50}" y="{pad + h + 28}">commanded speed [m/s]</text>')
        parts.append(f'<text x="{x0 - 28}" y="{pad + 4}">{ymax:g}</text><text x="{x0 - 12}" y="{pad + h}">0</text>')
        if i == 1:
            parts.append(f'<line x1="{x(0)}" y1="{y(0)}" x2="{x(vmax)}" y2="{y(vmax)}" stroke="#ccc" stroke-dasharray="4"/>')
        for k, d in enumerate(densities):
            colour = colours[k % len(colours)]
            points = [(x(c["speed_mps"]), y(value(c))) for c in grid
                      if c["m2_per_tree"] == m2_per_tree(d) and value(c) is not None]
            if points:
                parts.append('<polyline fill="none" stroke="{}" stroke-width="2" points="{}"/>'.format(
                    colour, " ".join(f"{px:.1f},{py:.1f}" for px, py in points)))
                parts.extend(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="3" fill="{colour}"/>' for px, py in points)
            if i == 0:
                parts.append(f'<text x="{x0 + 8}" y="{pad + h - 10 - 14 * k}" fill="{colour}">'
                             f'one tree per {m2_per_tree(d)} m²</text>')
    parts.append("</svg>")
    return "\n".join(parts)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    path = sys.argv[1]
    try:
        campaign = json.load(open(path))
        axes, runs = campaign["axes"], campaign["runs"]
        densities, speeds = axes[DENSITY], axes[SPEED]
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"forest_grid.py: {path}: not a campaign swept over {DENSITY} and {SPEED} ({e})")
    out = os.path.dirname(os.path.abspath(path))
    grid = []
    for d in densities:
        for v in speeds:
            cell_runs = [r for r in runs if r["params"].get(DENSITY) == d and r["params"].get(SPEED) == v]
            if cell_runs:
                grid.append(cell(cell_runs, d, v))
    f = lambda x: "-" if x is None else f"{x:.2f}"
    print(f"{'m2/tree':>7} {'m/s':>4} {'success':>8} {'avg m/s':>8} {'top m/s':>8} {'to goal s':>9} "
          f"{'flown/opt':>9} {'closest m':>9} {'latency s':>9} {'est rms m':>9} {'NEES':>6}")
    for c in grid:
        print(f"{c['m2_per_tree']:>7g} {c['speed_mps']:>4g} {c['successes']:>4}/{c['runs']:<3} "
              f"{f(c['average_speed_mps']):>8} {f(c['top_speed_mps']):>8} {f(c['time_to_goal_s']):>9} "
              f"{f(c['flown_over_optimum']):>9} {f(c['closest_approach_m']):>9} "
              f"{f(c['depth_to_command_max_s']):>9} {f(c['estimate_rms_m']):>9} {f(c['estimate_nees']):>6}")
    json.dump({"grid": grid}, open(f"{out}/grid.json", "w"), indent=2)
    open(f"{out}/grid.svg", "w").write(svg(grid, densities, speeds))
    print(f"grid in {out}/grid.json and {out}/grid.svg (speeds, times and lengths: medians over the "
          "successful runs; the closest approach and the latency from a depth frame to its command: the "
          "worst of all runs; the estimate's position error (RMS) and mean NEES: medians over all)")


if __name__ == "__main__":
    main()
