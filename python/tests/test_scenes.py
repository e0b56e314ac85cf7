"""Scene files from Python: a file read, built and stepped; a built-in scene's reference state."""
import json

import pytest

import collide


def test_a_scene_file_is_read_built_and_stepped(tmp_path):
    scene_file = tmp_path / "drop.json"
    scene_file.write_text(json.dumps({
        "format": "collide-scene/1",
        "settings": {"dt": 1 / 60, "steps": 120},
        "bodies": [
            {"name": "ground", "type": "static", "shape": {"type": "plane", "normal": [0, 1, 0], "distance": 0}},
            {"name": "ball", "type": "dynamic", "shape": {"type": "sphere", "radius": 0.5}, "position": [0, 2, 0]},
        ]}))
    scene = collide.load_scene(str(scene_file))
    assert scene.body_count == 2 and scene.steps == 120
    built = collide.build_world(scene)
    world = built.world
    ball = built.bodies[1]
    assert world.name(ball) == "ball"
    world.steps(scene.dt, scene.steps)
    assert world.position(ball)[1] == pytest.approx(0.5, abs=0.01)


# The reference hash of `billiards` after 120 steps (tests/scene/reference_hashes_test.cpp): it holds
# for GCC's Release build on x86-64, which this module is when built by CMake or setup.py there.
BILLIARDS_120_STEPS = 0x72ce044392ccc8d0


@pytest.mark.skipif(not collide._collide.reference_build,
                    reason="the reference hashes hold for the reference build only (docs/determinism.md)")
def test_a_builtin_scene_ends_in_its_reference_state():
    scene = collide.builtin_scene("billiards")
    built = collide.build_world(scene)
    built.world.steps(scene.dt, 120)
    assert built.state_hash() == BILLIARDS_120_STEPS


def test_a_scene_runs_the_same_twice():
    hashes = []
    for _ in range(2):
        scene = collide.builtin_scene("pile")
        built = collide.build_world(scene)
        built.world.steps(scene.dt, 30)
        hashes.append((built.state_hash(), built.world.positions().tobytes()))
    assert hashes[0] == hashes[1]
