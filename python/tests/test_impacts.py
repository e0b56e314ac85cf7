"""The lecture's impact laws, checked from Python against their formulas."""
import math

import pytest

import collide

DT = 1.0 / 60.0


def head_on(m1, v1, m2, v2, e, impact_model="newton"):
    world = collide.World(gravity=(0, 0, 0), impact_model=impact_model)
    a = world.create_body(collide.Sphere(0.5), position=(-1, 0, 0), velocity=(v1, 0, 0), mass=m1,
                          bounciness=e, friction=0)
    b = world.create_body(collide.Sphere(0.5), position=(1, 0, 0), velocity=(v2, 0, 0), mass=m2,
                          bounciness=e, friction=0)
    p0 = world.linear_momentum()
    world.steps(DT, 90)
    return world, world.velocity(a)[0], world.velocity(b)[0], p0


def newton_1d(m1, v1, m2, v2, e):
    """Newton's impact law with conservation of momentum along the line of the impact."""
    u1 = (m1 * v1 + m2 * v2 + m2 * e * (v2 - v1)) / (m1 + m2)
    u2 = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2)
    return u1, u2


def test_equal_masses_swap_their_velocities():
    world, u1, u2, p0 = head_on(1.0, 1.0, 1.0, -1.0, 1.0)
    assert u1 == pytest.approx(-1.0, abs=0.01)
    assert u2 == pytest.approx(1.0, abs=0.01)
    assert world.kinetic_energy() == pytest.approx(1.0, rel=0.01)


@pytest.mark.parametrize("m1,v1,m2,v2,e", [(1, 2, 3, -1, 1), (5, 1.5, 0.5, 0, 1), (2, 3, 1, -2, 0.5),
                                           (1, 2, 4, 0, 0.25)])
@pytest.mark.parametrize("model", ["newton", "interpolated"])
def test_impacts_match_the_formula_and_keep_momentum(m1, v1, m2, v2, e, model):
    world, u1, u2, p0 = head_on(m1, v1, m2, v2, e, model)
    expected1, expected2 = newton_1d(m1, v1, m2, v2, e)
    scale = max(abs(v1), abs(v2))
    assert u1 == pytest.approx(expected1, abs=0.01 * scale)
    assert u2 == pytest.approx(expected2, abs=0.01 * scale)
    p1 = world.linear_momentum()
    assert math.dist(p0, p1) <= 1e-4 * (abs(m1 * v1) + abs(m2 * v2))


def test_fully_inelastic_means_a_shared_velocity():
    world, u1, u2, _ = head_on(2.0, 3.0, 1.0, -3.0, 0.0)
    shared = (2.0 * 3.0 + 1.0 * -3.0) / 3.0
    assert u1 == pytest.approx(shared, abs=0.03)
    assert u2 == pytest.approx(shared, abs=0.03)


def test_a_static_wall_flips_the_normal_component_and_keeps_the_tangential_one():
    world = collide.World(gravity=(0, 0, 0))
    world.create_body(collide.Box((0.5, 5, 5)), type="static", position=(2, 0, 0), friction=0, bounciness=1)
    ball = world.create_body(collide.Sphere(0.5), velocity=(3, 0, 1), mass=1, bounciness=1, friction=0)
    world.steps(DT, 60)
    vx, vy, vz = world.velocity(ball)
    assert vx == pytest.approx(-3.0, abs=0.03)
    assert vz == pytest.approx(1.0, abs=0.01)
    assert vy == pytest.approx(0.0, abs=1e-4)


def test_bounciness_combines_by_the_world_rule():
    # The ball's bounciness 1 against the floor's 0: max gives 1, min gives 0, average 0.5.
    for rule, e in [("max", 1.0), ("min", 0.0), ("average", 0.5)]:
        world = collide.World(gravity=(0, 0, 0), bounciness_combine=rule)
        world.create_body(collide.Plane((0, 1, 0), 0), type="static", bounciness=0, friction=0)
        ball = world.create_body(collide.Sphere(0.5), position=(0, 2, 0), velocity=(0, -4, 0), mass=1,
                                 bounciness=1, friction=0)
        world.steps(DT, 60)
        assert world.velocity(ball)[1] == pytest.approx(4.0 * e, abs=0.05), rule
