#!/usr/bin/env python3
"""How the step grows with the bodies: R1's lattice of unit cubes (spacing 1.1, lowest layer at
y = 1, on R1's 200 x 200 m ground) widened from 16 x 16 x 16 to 32 x 16 x 32 and 64 x 16 x 64
(65,536 cubes). For each, `collide bench` over the first STEPS steps (ms per step, the world's heap
by stage) and `/usr/bin/time -f %M collide run` over the same steps (the whole process's peak).
--spacing S spaces the columns S apart in x and z instead (2.0: stacks that never touch, an island
each).

    bench/pile_growth.py build/release/tools/collide [--steps 240] [--spacing 1.1] [--csv FILE --commit C]
"""
import argparse
import json
import re
import subprocess
import tempfile
from datetime import date
from pathlib import Path


def lattice_scene(nx, ny, nz, spacing=1.1):
    bodies = [{"name": "ground", "type": "static", "friction": 0.5, "position": [0.0, -0.5, 0.0],
               "shape": {"type": "box", "half_extents": [100.0, 0.5, 100.0]}}]
    for i in range(nx):
        for j in range(ny):
            for k in range(nz):
                bodies.append({"name": f"box_{i}_{j}_{k}", "type": "dynamic", "mass": 1, "friction": 0.5,
                               "position": [(i - (nx - 1) / 2) * spacing, 1.0 + 1.1 * j, (k - (nz - 1) / 2) * spacing],
                               "shape": {"type": "box", "half_extents": [0.5, 0.5, 0.5]}})
    return {"format": "collide-scene/1",
            "settings": {"broadphase": "tree", "dt": 1.0 / 60.0, "friction_combine": "average",
                         "gravity": [0.0, -9.81, 0.0], "sleeping": False, "steps": 600},
            "bodies": bodies}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("collide")
    parser.add_argument("--steps", type=int, default=240)
    parser.add_argument("--spacing", type=float, default=1.1)
    parser.add_argument("--csv")
    parser.add_argument("--commit", default="")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for nx, ny, nz in [(16, 16, 16), (32, 16, 32), (64, 16, 64)]:
            path = Path(folder) / f"pile_{nx}x{ny}x{nz}.json"
            path.write_text(json.dumps(lattice_scene(nx, ny, nz, args.spacing)))
            bench = subprocess.run([args.collide, "bench", str(path), "--runs", "1", "--steps", str(args.steps)],
                                   check=True, capture_output=True, text=True).stdout
            ms = float(re.search(r"median: ([0-9.]+) ms/step \(cpu\)", bench).group(1))
            world_mb = float(re.search(r"^world\s+([0-9.]+)", bench, re.M).group(1))
            timed = subprocess.run(["/usr/bin/time", "-f", "%M", args.collide, "run", str(path), "--steps",
                                    str(args.steps)], check=True, capture_output=True, text=True)
            peak_mb = int(timed.stderr.strip().splitlines()[-1]) / 1024
            bodies = nx * ny * nz
            rows.append((bodies, ms, world_mb, peak_mb))
            print(f"{nx} x {ny} x {nz}: {bodies} cubes, {ms:.2f} ms/step, world heap {world_mb:.1f} MB, "
                  f"process peak {peak_mb:.1f} MB")
    first = rows[0]
    for bodies, ms, world_mb, peak_mb in rows[1:]:
        print(f"{bodies} / {first[0]} cubes ({bodies / first[0]:.0f}x): time {ms / first[1]:.1f}x, "
              f"world heap {world_mb / first[2]:.1f}x")
    if args.csv:
        new = not Path(args.csv).exists()
        with open(args.csv, "a") as out:
            if new:
                out.write("date,commit,steps,cubes,ms_per_step,world_heap_mb,process_peak_mb\n")
            for bodies, ms, world_mb, peak_mb in rows:
                out.write(f"{date.today()},{args.commit},{args.steps},{bodies},{ms:.3f},{world_mb:.3f},{peak_mb:.1f}\n")


if __name__ == "__main__":
    main()
