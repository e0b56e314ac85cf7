"""Bad input raises collide.Error (a ValueError) with the library's message, and changes nothing."""
import math

import numpy as np
import pytest

import collide


def test_bad_sizes_and_values_name_what_is_wrong():
    world = collide.World()
    with pytest.raises(collide.Error, match="radius"):
        world.create_body(collide.Sphere(-1))
    with pytest.raises(collide.Error, match="position"):
        world.create_body(collide.Sphere(0.5), position=(math.nan, 0, 0))
    with pytest.raises(collide.Error, match='type: must be "static", "kinematic" or "dynamic"'):
        world.create_body(collide.Sphere(0.5), type="flying")
    with pytest.raises(collide.Error, match="impact model"):
        collide.World(impact_model="sticky")
    with pytest.raises(collide.Error):
        collide.ConvexHull(np.zeros((4, 3)))  # a degenerate hull
    with pytest.raises(collide.Error, match="out of range"):
        collide.TriangleMesh(np.zeros((3, 3)), np.array([[0, 1, 5]]))
    assert world.body_count == 0
    assert issubclass(collide.Error, ValueError)


def test_a_destroyed_body_is_refused():
    world = collide.World()
    ball = world.create_body(collide.Sphere(0.5))
    world.destroy_body(ball)
    assert not world.is_valid(ball)
    with pytest.raises(collide.Error):
        world.position(ball)


def test_a_bad_scene_names_the_field():
    with pytest.raises(collide.Error, match=r"bodies\[0\]\.shape\.radius"):
        collide.parse_scene('{"format": "collide-scene/1", "bodies": [{"name": "b", "type": "dynamic", '
                            '"shape": {"type": "sphere", "radius": -1}}]}')
    with pytest.raises(collide.Error):
        collide.builtin_scene("no-such-scene")
    with pytest.raises(collide.Error):
        collide.load_scene("/nonexistent/scene.json")


def test_a_bad_compound_child_is_named():
    with pytest.raises(collide.Error, match=r"children\[0\]: the first item must be a collide shape"):
        collide.Compound([(1, (0, 0, 0))])
    with pytest.raises(collide.Error, match=r"children\[1\]: position must be 3 numbers"):
        collide.Compound([(collide.Sphere(1), (0, 0, 0)), (collide.Sphere(1), (0, 0))])


def test_bad_joint_limits_and_motors_are_named():
    world = collide.World()
    post = world.create_body(collide.Sphere(0.1), type="static")
    arm = world.create_body(collide.Sphere(0.1), position=(1, 0, 0))
    with pytest.raises(collide.Error, match=r"limits: must be \(lower, upper\)"):
        world.create_hinge_joint(post, arm, (0, 0, 0), (0, 0, 1), limits=(1.0,))
    with pytest.raises(collide.Error, match=r"motor: must be \(speed, max_force\)"):
        world.create_slider_joint(post, arm, (0, 0, 0), (1, 0, 0), motor=(1.0, 2.0, 3.0))
    assert world.joint_count == 0
