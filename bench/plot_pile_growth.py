#!/usr/bin/env python3
"""Plots how the step's time and memory grow with the bodies (bench/pile_growth.py's rows):
    python3 bench/plot_pile_growth.py bench/results/pile_growth.csv docs/images/pile_growth.png [--commit C]
The newest commit's rows (the median of its runs) unless --commit names one; log-log, with the linear growth from the
smallest lattice dashed beside each measure. Uses matplotlib (Debian's python3-matplotlib)."""
import argparse
import csv
import statistics

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv")
    parser.add_argument("png")
    parser.add_argument("--commit")
    args = parser.parse_args()
    with open(args.csv) as f:
        rows = list(csv.DictReader(f))
    commit = args.commit or rows[-1]["commit"]
    rows = [r for r in rows if r["commit"] == commit]
    # Several runs of the commit: the median of each size's runs.
    cubes = sorted({int(r["cubes"]) for r in rows})
    def median(key, n):
        return statistics.median(float(r[key]) for r in rows if int(r["cubes"]) == n)
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, label, color in [("ms_per_step", "ms per step", "tab:blue"),
                              ("world_heap_mb", "world heap, MB", "tab:orange"),
                              ("process_peak_mb", "process peak, MB", "tab:green")]:
        values = [median(key, n) for n in cubes]
        ax.plot(cubes, values, "o-", color=color, label=label)
        ax.plot(cubes, [values[0] * n / cubes[0] for n in cubes], "--", color=color, alpha=0.5)
    ax.set_xscale("log", base=2)
    ax.set_yscale("log")
    ax.set_xticks(cubes, [f"{n:,}" for n in cubes])
    ax.set_xlabel("cubes (R1's lattice widened)")
    ax.set_title(f"Growth over the first {rows[0]['steps']} steps ({rows[0]['date']}, {commit}); dashed: linear")
    ax.legend()
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.png, dpi=100)


if __name__ == "__main__":
    main()
