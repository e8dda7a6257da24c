"""The one elementary-rotation helper, against the matrices written out by hand."""

import math
import random

import pytest
import torch

from radaraug.scene.people._rotations import axis_rotation, euler_from_matrix, matrix_from_euler


def written_out(axis: str, a: float) -> torch.Tensor:
    c, s = math.cos(a), math.sin(a)
    m = {
        "x": [[1, 0, 0], [0, c, -s], [0, s, c]],
        "y": [[c, 0, s], [0, 1, 0], [-s, 0, c]],
        "z": [[c, -s, 0], [s, c, 0], [0, 0, 1]],
    }[axis]
    return torch.tensor(m, dtype=torch.float64)


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_a_float_angle_gives_the_written_out_matrix_bit_for_bit(axis):
    # Scene poses, room objects and recorded people use float angles: their matrices must not move.
    rng = random.Random(0)
    angles = [0.0, -0.0, math.pi / 2, math.pi, -math.pi / 3, 1e-9] + [rng.uniform(-20, 20) for _ in range(500)]
    for a in angles:
        assert torch.equal(axis_rotation(axis, a), written_out(axis, a)), a


@pytest.mark.parametrize("axis", ["x", "y", "z"])
def test_tensor_angles_are_rotations_about_the_axis(axis):
    a = torch.linspace(-4, 4, 33, dtype=torch.float64)
    r = axis_rotation(axis, a)
    ref = torch.stack([written_out(axis, float(v)) for v in a])
    torch.testing.assert_close(r, ref, rtol=0, atol=1e-15)
    k = "xyz".index(axis)
    torch.testing.assert_close(r[:, :, k], torch.eye(3, dtype=torch.float64)[k].expand(33, 3))  # axis kept


def test_euler_round_trip():
    angles = torch.tensor([[0.3, -0.4, 1.2], [-2.0, 0.1, 0.5]], dtype=torch.float64)
    torch.testing.assert_close(euler_from_matrix(matrix_from_euler(angles, "zxy"), "zxy"), angles)
