"""The character mover from Python: the walk, stairs and crouching of docs/character.md."""
import pytest

import collide

DT = 1.0 / 60.0


def flat_world():
    world = collide.World()
    world.create_body(collide.Box((50, 0.5, 50)), type="static", position=(0, -0.5, 0))
    return world


def standing(x=0.0, z=0.0):
    return collide.Character((x, 0.02 + 0.3 + 0.6, z))


def test_it_walks_flat_ground_at_the_speed_asked():
    world, character = flat_world(), standing()
    for _ in range(120):
        world.step(DT)
        character.update(world, (5, 0, 0), DT)
        assert character.ground_state == "on ground"
    assert character.position[0] == pytest.approx(10.0, rel=0.01)
    assert abs(character.foot_position[1] - 0.02) < 1e-3


def test_it_climbs_a_step_it_can_and_stops_at_one_it_cannot():
    for rise, climbs in [(0.3, True), (0.4, False)]:
        world, character = flat_world(), standing()
        world.create_body(collide.Box((2, rise / 2, 2)), type="static", position=(3, rise / 2, 0))
        for _ in range(120):
            world.step(DT)
            character.update(world, (2, 0, 0), DT)
        if climbs:
            assert character.foot_position[1] == pytest.approx(rise + 0.02, abs=0.05)
        else:
            assert character.foot_position[1] < 0.1 and character.position[0] < 1.0


def test_it_crouches_under_a_beam_and_stands_only_past_it():
    world, character = flat_world(), standing()
    world.create_body(collide.Box((1, 0.2, 2)), type="static", position=(3, 1.6, 0))
    world.step(DT)
    character.update(world, (0, 0, 0), DT)
    assert character.set_half_height(world, 0.2)
    for _ in range(90):
        world.step(DT)
        character.update(world, (2, 0, 0), DT)
    assert 2.5 < character.position[0] < 3.8
    assert not character.set_half_height(world, 0.6)
    for _ in range(60):
        world.step(DT)
        character.update(world, (2, 0, 0), DT)
    assert character.set_half_height(world, 0.6)


def test_bad_definitions_are_refused_by_name():
    with pytest.raises(collide.Error, match="radius"):
        collide.Character((0, 1, 0), radius=-1)
