#!/usr/bin/env python3
"""Plots collide / Bullet time per step for each reference scene, with the project's goal for each
(the JSON's "target"), from the JSON of collide_vs_bullet:
    build/bench/bench/vs_bullet/collide_vs_bullet --runs 3 --json vs_bullet.json
    python3 bench/plot_vs_bullet.py vs_bullet.json docs/images/vs_bullet_ratio.png
Uses gnuplot (apt-get install gnuplot-nox), so that no Python package is needed."""
import json
import os
import subprocess
import sys
import tempfile


def main(json_path, png_path):
    with open(json_path) as f:
        scenes = json.load(f)["scenes"]
    with tempfile.TemporaryDirectory() as tmp:
        data = os.path.join(tmp, "ratio.dat")
        with open(data, "w") as out:
            for i, s in enumerate(scenes):
                target = s["target"] if s["target"] is not None else "NaN"
                label = f'{s["id"]} {s["name"]}'
                # The median of the runs' own ratios where the JSON has it (each run times both
                # engines back to back, so a slow spell of the host weighs on both).
                ratio = s.get("median_run_ratio", s["ratio"])
                out.write(f'{i} "{label}" {ratio} {target}\n')
        script = "\n".join([
            "set terminal pngcairo size 900,560 font ',11'" if has_cairo() else "set terminal png size 900,560",
            f"set output '{png_path}'",
            "set style fill solid 0.6 border -1",
            "set boxwidth 0.6",
            "set grid ytics",
            "set key top left",
            "set yrange [0:*]",
            f"set xrange [-0.6:{len(scenes) - 0.4}]",
            "set ylabel 'collide / Bullet, CPU time per step (lower is better)'",
            "set title 'collide vs Bullet 3.24 on the reference scenes (median of the per-run ratios)'",
            "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb 'gray40'",
            f"plot '{data}' using 1:3:xtic(2) with boxes lc rgb '#4477aa' title 'measured ratio', "
            f"'' using 1:3:(sprintf('%.2f', $3)) with labels offset 0,0.8 notitle, "
            f"'' using 1:4 with points pt 9 ps 2.5 lc rgb '#cc3311' title 'goal'",
        ])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def has_cairo():
    out = subprocess.run(["gnuplot", "-e", "set terminal"], capture_output=True, text=True)
    return "pngcairo" in (out.stdout + out.stderr)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
