#!/usr/bin/env python3
"""Plots the recorded collide / Bullet ratios of the reference scenes, one line per scene over the
rows of the history file (one row per recorded measurement, in order):
    python3 bench/plot_history.py bench/results/vs_bullet_history.csv docs/images/vs_bullet_history.png
Rows whose `series` is `main` are joined by a line; rows of other series (builds measured on a side
branch) are drawn as open points of the scene's colour. The dashed lines are the goals that
collide_vs_bullet checks (bench/vs_bullet/main.cpp). The y axis is logarithmic.
Uses gnuplot (apt-get install gnuplot-nox) and the standard library only."""
import csv
import os
import shutil
import subprocess
import sys
import tempfile

# Column, legend label, colour, goal (collide / Bullet below it), as in collide_vs_bullet.
SCENES = [
    ("R1", "R1 pile", "#4477aa", 0.34),
    ("R2", "R2 rain", "#66ccee", 0.67),
    ("R2_jittered", "R2 rain-jittered", "#228833", None),
    ("R3", "R3 pyramid", "#ccbb44", 0.63),
    ("R4", "R4 terrain", "#ee6677", 0.16),
    ("B1", "B1 billiards", "#aa3377", None),
]


def quoted(text):
    """A gnuplot single-quoted string."""
    return "'" + text.replace("'", "''") + "'"


def read_rows(csv_path):
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{csv_path}: no rows")
    for column in ["date", "series"] + [s[0] for s in SCENES]:
        if column not in rows[0]:
            sys.exit(f"{csv_path}: no column '{column}'")
    return rows


def main(csv_path, png_path):
    if shutil.which("gnuplot") is None:
        sys.exit("gnuplot not found (apt-get install gnuplot-nox)")
    rows = read_rows(csv_path)
    with tempfile.TemporaryDirectory() as tmp:
        plots = []
        for column, label, colour, goal in SCENES:
            # One data file per scene and series, holding only the rows that measured the scene, so
            # that a line joins a scene's measurements across the rows that left it out.
            by_series = {}
            for x, row in enumerate(rows, start=1):
                value = row[column].strip()
                if value:
                    by_series.setdefault(row["series"].strip() or "main", []).append((x, float(value)))
            for series, points in by_series.items():
                data = os.path.join(tmp, f"{column}_{len(plots)}.dat")
                with open(data, "w") as out:
                    out.writelines(f"{x} {y}\n" for x, y in points)
                if series == "main":
                    plots.append(f"'{data}' using 1:2 with linespoints lw 2 pt 7 ps 1.2 lc rgb '{colour}' "
                                 f"title {quoted(label)}")
                else:
                    plots.append(f"'{data}' using 1:2 with points pt 6 ps 1.6 lc rgb '{colour}' "
                                 f"title {quoted(label + ', ' + series)}")
            if goal is not None and by_series:
                plots.append(f"{goal} with lines dt 2 lw 1 lc rgb '{colour}' notitle")
        tics = ", ".join(f"{quoted(str(x) + '  ' + row['date'])} {x}" for x, row in enumerate(rows, start=1))
        script = "\n".join([
            "set terminal pngcairo size 1100,640 font ',10'" if has_cairo() else "set terminal png size 1100,640",
            f"set output '{png_path}'",
            "set logscale y",
            "set yrange [0.05:4]",
            "set ytics (0.05, 0.1, 0.16, 0.2, 0.34, 0.5, 0.67, 1, 2, 4)",
            "set grid ytics",
            f"set xrange [0.5:{len(rows) + 0.5}]",
            f"set xtics rotate by -60 font ',8' ({tics})",
            "set key outside right top",
            "set xlabel 'recorded measurement (row of the history file) and its date'",
            "set ylabel 'collide / Bullet, CPU time per step (lower is better)'",
            "set title 'collide vs Bullet 3.24 on the reference scenes, as recorded (dashed: the goals)'",
            "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 3 lc rgb 'gray40'",
            "plot " + ", \\\n     ".join(plots),
        ])
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def has_cairo():
    out = subprocess.run(["gnuplot", "-e", "set terminal"], capture_output=True, text=True)
    return "pngcairo" in (out.stdout + out.stderr)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_history.py HISTORY.csv OUT.png")
    main(sys.argv[1], sys.argv[2])
