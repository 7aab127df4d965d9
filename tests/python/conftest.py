"""Shared fixtures of the Python tests (CTest runs them with PYTHONPATH at
build/python and the helper programs' paths in the environment, see
tests/CMakeLists.txt)."""
import os
import subprocess

import numpy as np
import pytest

import clraster


@pytest.fixture(scope="session")
def ctx():
    return clraster.Context(os.environ.get("CLRASTER_TEST_DEVICE"))


@pytest.fixture(scope="session")
def helper():
    return os.environ["CLRASTER_API_HELPER"]


def oracle_ids(helper, tmp_path, pos, tri, height, width):
    """The scalar oracle's triangle id + 1 per pixel [H, W] (tests/api_helper.cpp)."""
    src, dst = tmp_path / "oracle_in.bin", tmp_path / "oracle_out.bin"
    with open(src, "wb") as f:
        np.array([width, height, len(pos), len(tri)], np.uint32).tofile(f)
        np.ascontiguousarray(pos, np.float32).tofile(f)
        np.ascontiguousarray(tri, np.uint32).tofile(f)
    subprocess.run([helper, "oracle-ids", str(src), str(dst)], check=True)
    return np.fromfile(dst, np.uint32).reshape(height, width)
