"""The batch example's physics: the first rebound of a dropped ball is e^2 times the drop."""
import importlib.util
from pathlib import Path

import pytest

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "batch_experiment.py"


def load_example():
    spec = importlib.util.spec_from_file_location("batch_experiment", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("radius,mass,bounciness,drop", [(0.1, 1.0, 0.9, 2.0), (0.4, 15.0, 0.5, 1.0),
                                                         (0.25, 0.2, 0.3, 3.0)])
def test_the_first_rebound_is_e_squared_of_the_drop(radius, mass, bounciness, drop):
    example = load_example()
    height = example.first_rebound_height(radius, mass, bounciness, drop)
    assert height / drop == pytest.approx(bounciness ** 2, abs=0.01)
