#!/usr/bin/env python3
"""collide at 1 and 2 workers on the reference scenes, with Bullet in the same run.

Each run steps every scene three times, in turn: collide with one worker, collide with two, and
Bullet (single-threaded; collide_vs_bullet runs it beside each collide run, so it is measured twice
a run). Figures are wall milliseconds per step (the CPU time counts every thread), medians over
the runs, and the fastest run of each: on a shared host the noise only ever slows a run, and
two workers far more than one (their hand-overs wait for the other vCPU), so the fastest runs say
what the machine can do and the medians what a run met. Prints a Markdown table and, with --csv,
appends dated rows.

  bench/workers_vs_bullet.py build/release/bench/vs_bullet/collide_vs_bullet --runs 3 --steps 300
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

SCENES = [("R1", "pile"), ("R2j", "rain-jittered"), ("R3", "pyramid"), ("R4", "terrain")]
TARGETS = {"R1": 1.7, "R2j": 1.7, "R3": 1.4, "R4": 1.7}  # the speedup at two workers aimed for


def measure(harness, scene, workers, steps):
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, "run.json")
        subprocess.run([harness, "--scene", scene, "--runs", "1", "--steps", str(steps), "--workers", str(workers),
                        "--json", path], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        with open(path) as f:
            result = json.load(f)["scenes"][0]
    return result["collide"]["wall_ms_per_step"], result["bullet"]["wall_ms_per_step"]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("harness", help="the collide_vs_bullet executable")
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--csv", help="append the figures to this CSV file")
    parser.add_argument("--commit", default="", help="the commit measured, for the CSV")
    args = parser.parse_args()

    one, two, bullet = {}, {}, {}
    for run in range(args.runs):
        for sid, name in SCENES:
            c1, b1 = measure(args.harness, name, 1, args.steps)
            c2, b2 = measure(args.harness, name, 2, args.steps)
            one.setdefault(sid, []).append(c1)
            two.setdefault(sid, []).append(c2)
            bullet.setdefault(sid, []).extend([b1, b2])
            print(f"run {run + 1}/{args.runs} {sid:4} 1 worker {c1:8.3f}  2 workers {c2:8.3f}  Bullet {b1:8.3f} {b2:8.3f}",
                  file=sys.stderr)

    date = datetime.date.today().isoformat()
    print(f"Wall ms per step, median (and fastest) of {args.runs} runs of {args.steps} steps ({date}).\n")
    print("| scene | collide, 1 worker | collide, 2 workers | 1 / 2 workers | fastest runs, 1 / 2 workers | target "
          "| Bullet | collide 2 workers / Bullet |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    rows = []
    for sid, name in SCENES:
        m1, m2, mb = statistics.median(one[sid]), statistics.median(two[sid]), statistics.median(bullet[sid])
        f1, f2 = min(one[sid]), min(two[sid])
        rows.append((sid, name, m1, m2, mb, f1, f2))
        print(f"| {sid} {name} | {m1:.3f} ({f1:.3f}) | {m2:.3f} ({f2:.3f}) | {m1 / m2:.2f} | {f1 / f2:.2f} "
              f"| {TARGETS[sid]:.1f} | {mb:.3f} | {m2 / mb:.2f} |")
    if args.csv:
        new = not os.path.exists(args.csv)
        with open(args.csv, "a") as f:
            if new:
                f.write("date,commit,scene,steps,runs,collide_1_worker_ms,collide_2_workers_ms,speedup,bullet_ms,"
                        "fastest_1_worker_ms,fastest_2_workers_ms,fastest_speedup\n")
            for sid, name, m1, m2, mb, f1, f2 in rows:
                f.write(f"{date},{args.commit},{sid},{args.steps},{args.runs},{m1:.4f},{m2:.4f},{m1 / m2:.3f},{mb:.4f},"
                        f"{f1:.4f},{f2:.4f},{f1 / f2:.3f}\n")


if __name__ == "__main__":
    main()
