#!/usr/bin/env python3
"""`collide fit` on a large mesh: a UV sphere of about 200,000 vertices, written here (the file is
12 MB, too large to keep in the repository). The command must succeed, say on stderr what its long
stages do, and time the convex hull's tests on fewer queries than the small proxies' (each pass of a
measure is bounded in time, so the timing stays short however large the hull)."""
import math
import os
import subprocess
import sys


def write_sphere(path, rings, segments):
    with open(path, "w") as out:
        out.write("v 0 1 0\n")
        for i in range(1, rings):
            theta = math.pi * i / rings
            for j in range(segments):
                phi = 2.0 * math.pi * j / segments
                out.write("v %.7f %.7f %.7f\n" % (math.sin(theta) * math.cos(phi), math.cos(theta),
                                                 math.sin(theta) * math.sin(phi)))
        out.write("v 0 -1 0\n")
        south = (rings - 1) * segments + 2

        def index(i, j):
            return 2 + (i - 1) * segments + j % segments

        for j in range(segments):
            out.write("f 1 %d %d\n" % (index(1, j + 1), index(1, j)))
        for i in range(1, rings - 1):
            for j in range(segments):
                out.write("f %d %d %d %d\n" % (index(i, j), index(i, j + 1), index(i + 1, j + 1), index(i + 1, j)))
        for j in range(segments):
            out.write("f %d %d %d\n" % (south, index(rings - 1, j), index(rings - 1, j + 1)))


def main():
    cli, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    mesh = os.path.join(work, "sphere200k.obj")
    write_sphere(mesh, 448, 448)
    run = subprocess.run([cli, "fit", mesh], capture_output=True, text=True)
    os.remove(mesh)
    print(run.stdout)
    print(run.stderr, file=sys.stderr)
    failures = []
    if run.returncode != 0:
        failures.append("exit code %d" % run.returncode)
    for text in ("collide fit: reading", "collide fit: fitting 9 proxies to 200258 points", "collide fit: fitted in",
                 "collide fit: timed in"):
        if text not in run.stderr:
            failures.append("stderr lacks %r" % text)
    if "convex_hull" not in run.stdout or "Fewer queries where a pass would take more than" not in run.stdout:
        failures.append("stdout lacks the hull's row or the note on its fewer queries")
    if failures:
        sys.exit("fit_large_mesh_check: " + "; ".join(failures))


if __name__ == "__main__":
    main()
