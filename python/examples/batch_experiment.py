"""A batch experiment: 1,000 small worlds with randomised parameters, one result plotted.

Each world drops a ball of random size, mass and bounciness from a random height onto a floor of
bounciness 0 (the ball's bounciness wins: the worlds combine by max) and records the top of its
first rebound. Newton's impact law says the rebound height is e^2 times the drop height; the script
prints how far the 1,000 measured ratios lie from e^2, and with matplotlib plots them
(rebound.png). Each world is independent, so they could run in parallel processes as well.

    python3 python/examples/batch_experiment.py [--worlds N] [--plot rebound.png]
"""
import argparse

import numpy as np

import collide

DT = 1.0 / 240.0  # a fine step, for the top of the rebound


def first_rebound_height(radius, mass, bounciness, drop):
    world = collide.World(bounciness_combine="max")
    world.create_body(collide.Plane((0, 1, 0)), type="static", bounciness=0.0, friction=0.0)
    ball = world.create_body(collide.Sphere(radius), position=(0, drop + radius, 0), mass=mass,
                             bounciness=bounciness, friction=0.0)
    bounced, top = False, 0.0
    for _ in range(int(4.0 / DT)):
        world.step(DT)
        vy = world.velocity(ball)[1]
        if not bounced and vy > 0:
            bounced = True
        if bounced:
            top = max(top, world.position(ball)[1] - radius)
            if vy <= 0:
                break
    return top


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--worlds", type=int, default=1000)
    parser.add_argument("--plot", default="rebound.png")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()

    rng = np.random.default_rng(args.seed)
    radius = rng.uniform(0.05, 0.5, args.worlds)
    mass = rng.uniform(0.1, 20.0, args.worlds)
    bounciness = rng.uniform(0.2, 1.0, args.worlds)
    drop = rng.uniform(0.5, 3.0, args.worlds)
    ratio = np.array([first_rebound_height(*p) for p in zip(radius, mass, bounciness, drop)]) / drop

    error = ratio - bounciness ** 2
    print(f"{args.worlds} worlds: rebound / drop height against e^2: "
          f"mean error {error.mean():+.4f}, largest {np.abs(error).max():.4f}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is not installed: no plot")
        return
    e = np.linspace(0.2, 1.0, 100)
    plt.plot(e, e ** 2, color="black", label="Newton: e²")
    plt.scatter(bounciness, ratio, s=4, alpha=0.5, label="collide, one world each")
    plt.xlabel("bounciness e")
    plt.ylabel("rebound height / drop height")
    plt.legend()
    plt.savefig(args.plot, dpi=100)
    print(f"plot: {args.plot}")


if __name__ == "__main__":
    main()
