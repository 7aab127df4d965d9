"""The library holds the CLI's resource rules: a call whose buffers exceed
the device's memory, the host's (under RLIMIT_AS too) or the Context's
memory_limit raises clraster.Error naming the size before allocating, never
a process killed or aborted; release() and garbage collection free what a
call kept."""
import gc
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import clraster

POS = np.array([[-1, -1, 0, 1], [1, -1, 0, 1], [0, 1, 0, 1]], np.float32)
TRI = np.array([[0, 1, 2]], np.int32)


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def run_limited(limit, code):
    """code in a fresh interpreter under RLIMIT_AS = limit: (exit status, output)."""
    script = textwrap.dedent(f"""
        import resource
        resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))
        import numpy as np, clraster
        POS = np.array([[-1, -1, 0, 1], [1, -1, 0, 1], [0, 1, 0, 1]], np.float32)
        TRI = np.array([[0, 1, 2]], np.int32)
        ctx = clraster.Context()
    """) + textwrap.dedent(code)
    r = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=600)
    return r.returncode, r.stdout + r.stderr


@pytest.mark.parametrize("side", [8192, 16384])
def test_large_rasterize_under_an_address_space_limit_is_an_error(side):
    # Without the check, 8192² under 3 GB ended in PoCL's assertion
    # (pocl_create_migration_commands), 16384² was killed.
    status, out = run_limited(3 << 30, f"""
        try:
            clraster.rasterize(ctx, POS, TRI, ({side}, {side}))
            print("rendered")
        except clraster.Error as e:
            print("refused:", e)
    """)
    assert status == 0, out
    assert "refused: rasterize at %dx%d needs " % (side, side) in out
    assert " bytes (" in out


def test_sizes_up_to_the_limit_either_render_or_are_refused():
    # Library calls with huge sizes: never an abort, whatever the limit.
    status, out = run_limited(2 << 30, """
        for side in (1024, 3000, 5000, 9000, 16384):
            for grad_db in (False, True):
                try:
                    clraster.rasterize(ctx, POS, TRI, (side, side), grad_db=grad_db)
                    print("rendered", side)
                except clraster.Error as e:
                    assert "bytes" in str(e), e
                    print("refused", side)
                ctx.release()
    """)
    assert status == 0, out
    assert "rendered 1024" in out
    assert "refused 16384" in out


def test_memory_limit_refuses_with_the_size():
    ctx = clraster.Context(memory_limit=1 << 20)
    assert ctx._ctx.memory_limit == 1 << 20
    with pytest.raises(clraster.Error, match=r"^rasterize at 512x512 needs .* bytes .*more than the limit of 1,048,576"):
        clraster.rasterize(ctx, POS, TRI, (512, 512))
    rast, _ = clraster.rasterize(ctx, POS, TRI, (16, 16), grad_db=False)
    assert (clraster.triangle_ids(rast) == 1).any()
    for bad in (0, -5):
        with pytest.raises(ValueError, match="^memory_limit: "):
            clraster.Context(memory_limit=bad)
    with pytest.raises(ValueError, match="^memory_limit: "):
        clraster.Context(memory_limit="1G")


def test_release_and_garbage_collection_free_what_a_call_kept():
    side = 4096
    kept = 30 * side * side  # the device buffers a call keeps (about 35 bytes a pixel)
    ctx = clraster.Context()
    clraster.rasterize(ctx, POS, TRI, (16, 16))
    before = resident_bytes()
    clraster.rasterize(ctx, POS, TRI, (side, side))
    assert resident_bytes() - before > kept
    ctx.release()
    assert resident_bytes() - before < kept / 4
    rast, _ = clraster.rasterize(ctx, POS, TRI, (16, 16))  # usable after release
    assert (clraster.triangle_ids(rast) == 1).any()
    other = clraster.Context()
    clraster.rasterize(other, POS, TRI, (side, side))
    assert resident_bytes() - before > kept
    del other
    gc.collect()
    assert resident_bytes() - before < kept / 4
