#!/usr/bin/env python3
"""Plots the broad-phase step time against the number of proxies from a Google Benchmark JSON file:
    build/bench/bench/collide_bench --benchmark_filter=step --benchmark_out=bp.json --benchmark_out_format=json
    python3 bench/plot_broadphase.py bp.json docs/images/broadphase_scaling.png
Uses gnuplot (apt-get install gnuplot-nox), so that no Python package is needed."""
import json
import os
import subprocess
import sys
import tempfile


def main(json_path, png_path):
    with open(json_path) as f:
        runs = json.load(f)["benchmarks"]
    series = {}
    for run in runs:
        name = run["name"].split("/min_time")[0]
        parts = name.split("/")
        if parts[0] == "stepCollide":
            label, n = "collide " + parts[1], int(parts[2])
        elif parts[0] == "stepBullet":
            label, n = "Bullet btDbvtBroadphase", int(parts[1])
        else:
            continue
        series.setdefault(label, []).append((n, run["cpu_time"]))  # milliseconds
    with tempfile.TemporaryDirectory() as tmp:
        plots = []
        for i, (label, points) in enumerate(sorted(series.items())):
            data = os.path.join(tmp, f"{i}.dat")
            with open(data, "w") as out:
                for n, ms in sorted(points):
                    out.write(f"{n} {ms}\n")
            plots.append(f"'{data}' using 1:2 with linespoints lw 2 pt 7 title '{label}'")
        script = "\n".join([
            "set terminal pngcairo size 900,600 font ',11'" if has_cairo() else "set terminal png size 900,600",
            f"set output '{png_path}'",
            "set logscale xy",
            "set xrange [700:150000]",
            "set grid",
            "set key top left",
            "set xlabel 'moving proxies (random walk, about 0.05 partners per box)'",
            "set ylabel 'update + pair finding per step (ms, CPU)'",
            "set title 'collide broad phase scaling vs Bullet btDbvtBroadphase'",
            "plot " + ", ".join(plots),
        ])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def has_cairo():
    out = subprocess.run(["gnuplot", "-e", "set terminal"], capture_output=True, text=True)
    return "pngcairo" in (out.stdout + out.stderr)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
