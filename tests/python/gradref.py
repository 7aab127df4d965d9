"""Float64 references for the gradient tests: nvdiffrast's rasterize and
interpolate outputs as formulas of the inputs at the pixel centres (coverage
held fixed: each pixel keeps the triangle clraster gave it), and central
differences of any such function."""
import numpy as np


def pixel_ndc(height, width):
    y, x = np.mgrid[0:height, 0:width]
    return (2.0 * x + 1.0) / width - 1.0, (2.0 * y + 1.0) / height - 1.0


def rast_formula(pos, tri, ids, height, width):
    """(u, v, z/w, du/dX, du/dY, dv/dX, dv/dY) float64 [..., 7] per pixel of
    one image, 0 where ids is 0; pos [V, 4] float64, ids [H, W] (id + 1)."""
    out = np.zeros((height, width, 7))
    covered = ids > 0
    xn, yn = pixel_ndc(height, width)
    s = np.stack([xn[covered], yn[covered], np.ones(covered.sum())], 1)
    t = tri[ids[covered] - 1]
    p = [pos[t[:, i]][:, [0, 1, 3]] for i in range(3)]
    z = [pos[t[:, i], 2] for i in range(3)]
    r = [np.cross(p[1], p[2]), np.cross(p[2], p[0]), np.cross(p[0], p[1])]
    k = [np.sum(ri * s, 1) for ri in r]
    big_s = k[0] + k[1] + k[2]
    big_r = r[0] + r[1] + r[2]
    lam = [ki / big_s for ki in k]
    zw = sum(k[i] * z[i] for i in range(3)) / sum(k[i] * p[i][:, 2] for i in range(3))
    db = []
    for i in range(2):
        db.append((r[i][:, 0] - lam[i] * big_r[:, 0]) / big_s * 2 / width)
        db.append((r[i][:, 1] - lam[i] * big_r[:, 1]) / big_s * 2 / height)
    out[covered] = np.stack([lam[0], lam[1], zw] + db, 1)
    return out


def interpolate_formula(attr, rast, db, tri, ids, diff):
    """(out [H, W, C], out_da [H, W, 2·len(diff)]) float64 of one image."""
    out = np.zeros(rast.shape[:2] + (attr.shape[1],))
    out_da = np.zeros(rast.shape[:2] + (2 * len(diff),))
    covered = ids > 0
    t = tri[ids[covered] - 1]
    a0, a1, a2 = attr[t[:, 0]], attr[t[:, 1]], attr[t[:, 2]]
    u, v = rast[covered][:, 0:1], rast[covered][:, 1:2]
    out[covered] = u * a0 + v * a1 + (1 - u - v) * a2
    if diff:
        d = db[covered]
        dsdu, dsdv = (a0 - a2)[:, diff], (a1 - a2)[:, diff]
        da = np.empty((len(d), 2 * len(diff)))
        da[:, 0::2] = d[:, 0:1] * dsdu + d[:, 2:3] * dsdv
        da[:, 1::2] = d[:, 1:2] * dsdu + d[:, 3:4] * dsdv
        out_da[covered] = da
    return out, out_da


def central_differences(f, x, eps):
    """d f / d x by central differences, f a scalar function of the float64 array x."""
    g = np.zeros_like(x)
    flat, gflat = x.reshape(-1), g.reshape(-1)
    for i in range(flat.size):
        keep = flat[i]
        flat[i] = keep + eps
        up = f(x)
        flat[i] = keep - eps
        down = f(x)
        flat[i] = keep
        gflat[i] = (up - down) / (2 * eps)
    return g


def assert_close(got, want, rel, what):
    """got within rel of want's largest magnitude (float32 kernels against a float64 reference)."""
    scale = np.abs(want).max()
    assert scale > 0, f"{what}: the reference gradient is all zero"
    err = np.abs(got - want).max()
    assert err <= rel * scale, f"{what}: max error {err:.3g} against scale {scale:.3g}"
