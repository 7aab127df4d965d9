"""The nvdiffrast sample ports in examples/ converge (small sizes for CI):
pose recovers a rotation 25° away to within 2° in 300 iterations, from
two random targets; cube brings jittered corners and random colours to a
fifth of their starting error in 300 iterations; earth brings a grey
texture, sampled through every mip level, to a fifth of its texel error
in 200."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "examples"))

import cube  # noqa: E402
import earth  # noqa: E402
import pose  # noqa: E402


def test_pose_recovers_a_rotation_25_degrees_away():
    for seed in (1, 2):
        history = pose.run(iterations=300, resolution=48, seed=seed)
        assert history[0][2] > 24.9
        assert history[-1][2] < 2.0, f"seed {seed}: {history[-1][2]:.2f} degrees left"


def test_cube_recovers_positions_and_colours():
    history = cube.run(iterations=300, resolution=48)
    (_, loss0, pos0, col0), (_, loss1, pos1, col1) = history[0], history[-1]
    assert pos1 < pos0 / 5 and col1 < col0 / 5 and loss1 < loss0 / 10


def test_earth_recovers_a_mipmapped_texture():
    history = earth.run(iterations=200, resolution=48)
    (_, loss0, err0), (_, loss1, err1) = history[0], history[-1]
    assert err1 < err0 / 5 and loss1 < loss0 / 100
