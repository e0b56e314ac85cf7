"""Bodies, NumPy state, queries, joints, events and snapshots."""
import math

import numpy as np
import pytest

import collide

DT = 1.0 / 60.0


def test_free_fall_follows_the_integrator_exactly():
    # Semi-implicit Euler over substeps h: after N substeps y = y0 - g h^2 N (N + 1) / 2.
    world = collide.World(substeps=6)
    ball = world.create_body(collide.Sphere(0.5), position=(0, 100, 0))
    world.steps(DT, 60)
    h, n = DT / 6, 360
    assert world.position(ball)[1] == pytest.approx(100 - 9.81 * h * h * n * (n + 1) / 2, abs=1e-3)
    assert world.velocity(ball)[1] == pytest.approx(-9.81, rel=1e-4)


def test_state_arrays_match_the_bodies_one_by_one():
    world = collide.World()
    world.create_body(collide.Plane((0, 1, 0)), type="static")
    rng = np.random.default_rng(3)
    bodies = [world.create_body(collide.Box((0.3, 0.3, 0.3)), position=tuple(p))
              for p in rng.uniform((-5, 1, -5), (5, 8, 5), size=(50, 3))]
    world.steps(DT, 30)
    positions = world.positions(bodies)
    assert positions.shape == (50, 3) and positions.dtype == np.float32
    for i, body in enumerate(bodies):
        assert tuple(positions[i]) == pytest.approx(world.position(body))
    rotations = world.rotations(bodies)
    assert np.allclose(np.linalg.norm(rotations, axis=1), 1.0, atol=1e-5)
    assert world.positions().shape == (51, 3)  # every body, the plane first

    velocities = rng.uniform(-1, 1, size=(50, 3)).astype(np.float32)
    world.set_velocities(bodies, velocities)
    assert np.array_equal(world.velocities(bodies), velocities)
    with pytest.raises(collide.Error, match=r"shape \(50, 3\)"):
        world.set_velocities(bodies, velocities[:10])


def test_a_ball_comes_to_rest_on_the_ground():
    world = collide.World()
    world.create_body(collide.Plane((0, 1, 0)), type="static")
    ball = world.create_body(collide.Sphere(0.5), position=(0, 3, 0))
    world.steps(DT, 180)
    assert world.position(ball)[1] == pytest.approx(0.5, abs=0.01)
    assert abs(world.velocity(ball)[1]) < 1e-3


def test_queries_answer_with_the_geometry():
    world = collide.World()
    box = world.create_body(collide.Box((1, 0.5, 1)), type="static", position=(0, 0.5, 0))
    hit = world.cast_ray((0.2, 5, 0.3), (0, -1, 0))
    assert hit["body"] == box
    assert hit["distance"] == pytest.approx(4.0, abs=1e-5)
    assert hit["normal"] == pytest.approx((0, 1, 0))
    assert world.cast_ray((3, 5, 0), (0, -1, 0)) is None
    sweep = world.cast_shape(collide.Sphere(0.25), (0, 3, 0), (0, -4, 0))
    assert sweep["fraction"] * 4 == pytest.approx(3 - 1 - 0.25, abs=2e-3)
    assert world.overlap_shape(collide.Sphere(0.3), (0.9, 1.2, 0)) == [box]
    assert world.overlap_point((0, 0.25, 0)) == [box]
    assert not world.has_line_of_sight((-3, 0.5, 0), (3, 0.5, 0))
    assert world.has_line_of_sight((-3, 2, 0), (3, 2, 0))


def test_contact_events_name_the_bodies():
    world = collide.World()
    ground = world.create_body(collide.Plane((0, 1, 0)), type="static")
    ball = world.create_body(collide.Sphere(0.5), position=(0, 1, 0), velocity=(0, -3, 0))
    begins = []
    for _ in range(60):
        world.step(DT)
        begins += [e for e in world.contact_events() if e["type"] == "begin"]
    assert len(begins) == 1
    assert {begins[0]["a"], begins[0]["b"]} == {ground, ball}
    assert begins[0]["speed"] > 2.0


def test_a_distance_joint_keeps_its_length_and_a_hinge_swings():
    world = collide.World()
    anchor = world.create_body(collide.Sphere(0.1), type="static", position=(0, 5, 0))
    bob = world.create_body(collide.Sphere(0.1), position=(2, 5, 0))
    world.create_distance_joint(anchor, bob)
    world.steps(DT, 120)
    assert math.dist(world.position(bob), (0, 5, 0)) == pytest.approx(2.0, abs=0.01)

    door = world.create_body(collide.Box((0.5, 1, 0.05)), position=(10.5, 1, 0))
    post = world.create_body(collide.Box((0.05, 1, 0.05)), type="static", position=(9.95, 1, 0))
    hinge = world.create_hinge_joint(post, door, (10, 1, 0), (0, 1, 0), motor=(1.0, 1000.0))
    world.steps(DT, 60)
    assert world.joint_speed(hinge) == pytest.approx(1.0, abs=0.01)


def test_a_snapshot_restores_the_state_bit_for_bit():
    world = collide.World()
    world.create_body(collide.Plane((0, 1, 0)), type="static")
    for i in range(10):
        world.create_body(collide.Box((0.4, 0.4, 0.4)), position=(0.1 * i, 1 + i, 0))
    world.steps(DT, 20)
    snapshot = world.save_snapshot()
    world.steps(DT, 40)
    after = world.positions()
    world.load_snapshot(snapshot)
    world.steps(DT, 40)
    assert np.array_equal(world.positions(), after)
    with pytest.raises(collide.Error):
        world.load_snapshot(b"not a snapshot")


def test_shapes_give_mass_properties_at_uniform_density():
    props = collide.Sphere(0.5).mass_properties(density=1000)
    assert props["mass"] == pytest.approx(1000 * 4 / 3 * math.pi * 0.125, rel=1e-5)
    inertia = 2 / 5 * props["mass"] * 0.25
    assert np.allclose(props["inertia"], np.eye(3) * inertia, rtol=1e-5)
    cube = collide.ConvexHull(np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]))
    assert cube.mass_properties(density=1)["volume"] == pytest.approx(8.0, rel=1e-5)
    mesh = collide.TriangleMesh(np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1]]), np.array([[0, 2, 1]]))
    assert mesh.type == "mesh"
    assert collide.load_shape('{"type": "capsule", "radius": 0.5, "half_height": 1}').type == "capsule"


def test_a_slider_keeps_its_body_on_the_axis_and_a_limit_stops_it():
    # Gravity pulls the body down and sideways; the slider lets it move along x only, up to 1 m.
    world = collide.World(gravity=(-3, -9.81, 2))
    rail = world.create_body(collide.Box((0.1, 0.1, 0.1)), type="static", position=(0, 2, 0))
    cart = world.create_body(collide.Box((0.2, 0.2, 0.2)), position=(0, 2, 0), mass=5)
    slider = world.create_slider_joint(rail, cart, (0, 2, 0), (1, 0, 0), limits=(-1.0, 1.0))
    world.steps(DT, 180)
    x, y, z = world.position(cart)
    assert abs(y - 2) < 1e-3 and abs(z) < 1e-3
    assert x == pytest.approx(-1.0, abs=0.01)
    assert world.joint_position(slider) == pytest.approx(-1.0, abs=0.01)
    assert world.joint_type(slider) == "slider"


def test_a_fixed_joint_holds_and_a_break_force_lets_go_with_an_event():
    world = collide.World()
    post = world.create_body(collide.Box((0.1, 0.1, 0.1)), type="static", position=(0, 5, 0))
    light = world.create_body(collide.Box((0.2, 0.2, 0.2)), position=(0.5, 5, 0), mass=1)
    heavy = world.create_body(collide.Box((0.2, 0.2, 0.2)), position=(-0.5, 5, 0), mass=100)
    world.create_fixed_joint(post, light)
    weak = world.create_fixed_joint(post, heavy, break_force=200.0)  # 100 kg weighs 981 N
    breaks = []
    for _ in range(60):
        world.step(DT)
        breaks += world.joint_break_events()
    assert math.dist(world.position(light), (0.5, 5, 0)) < 1e-3
    assert [b["joint"] for b in breaks] == [weak]
    assert world.position(heavy)[1] < 4.0
    assert world.joint_count == 1


def test_a_cone_joint_keeps_its_swing_within_the_limit():
    world = collide.World()
    anchor = world.create_body(collide.Sphere(0.1), type="static", position=(0, 5, 0))
    limb = world.create_body(collide.Capsule(0.1, 0.5), position=(0, 4.4, 0), velocity=(3, 0, 0))
    world.create_cone_joint(anchor, limb, (0, 5, 0), (0, -1, 0), swing_limit=0.5)
    worst = 0.0
    for _ in range(120):
        world.step(DT)
        x, y, z = np.subtract(world.position(limb), (0, 5, 0))
        worst = max(worst, math.atan2(math.hypot(x, z), -y))
    assert 0.45 < worst < 0.5 + 0.02


def test_separate_worlds_step_in_threads_as_they_do_alone():
    from concurrent.futures import ThreadPoolExecutor

    def pile(seed):
        world = collide.World()
        world.create_body(collide.Plane((0, 1, 0)), type="static")
        rng = np.random.default_rng(seed)
        for p in rng.uniform((-2, 1, -2), (2, 6, 2), size=(40, 3)):
            world.create_body(collide.Box((0.3, 0.3, 0.3)), position=tuple(p))
        world.steps(DT, 120)
        return world.positions().tobytes()

    alone = [pile(seed) for seed in range(4)]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(pile, range(4)))
    assert threaded == alone
