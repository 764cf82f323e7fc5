"""The closest hit of each ray against every triangle, in double precision with numpy
(Moeller-Trumbore, no acceleration structure): an oracle independent of gridrt's code."""
import numpy as np

# Rays tested against all triangles at once: bounds the temporary arrays (rays x
# triangles doubles, a few of them) to some tens of MB.
RAYS_PER_CHUNK = 256


def triangle_hits(origins, directions, a, e1, e2):
    """For rays (R x 3) and triangles (vertex a, edges e1, e2; T x 3), the R x T arrays
    t, u, v of the ray's plane hit (nan where the ray is parallel to the triangle)."""
    p = np.cross(directions[:, None, :], e2[None, :, :])
    det = np.einsum("rtk,tk->rt", p, e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = origins[:, None, :] - a[None, :, :]
        u = np.einsum("rtk,rtk->rt", s, p) * inv
        q = np.cross(s, e1[None, :, :])
        v = np.einsum("rk,rtk->rt", directions, q) * inv
        t = np.einsum("rtk,tk->rt", q, e2) * inv
    parallel = det == 0.0
    t[parallel] = np.nan
    return t, u, v


def closest_hits(vertices, faces, origins, directions, tmax, inside=0.0):
    """Per ray: (t, prim, u, v) of the smallest t in (0, tmax] among triangles whose
    barycentrics are all >= -inside; prim -1 (t inf) where there is none. Equal t: the
    lowest triangle index, as gridrt's intersectors break ties."""
    vertices = np.asarray(vertices, np.float64)
    a = vertices[faces[:, 0]]
    e1 = vertices[faces[:, 1]] - a
    e2 = vertices[faces[:, 2]] - a
    n = len(origins)
    t_out = np.full(n, np.inf)
    prim = np.full(n, -1, np.int64)
    u_out = np.zeros(n)
    v_out = np.zeros(n)
    for first in range(0, n, RAYS_PER_CHUNK):
        rows = slice(first, min(n, first + RAYS_PER_CHUNK))
        o = np.asarray(origins[rows], np.float64)
        d = np.asarray(directions[rows], np.float64)
        t, u, v = triangle_hits(o, d, a, e1, e2)
        limit = np.asarray(tmax[rows], np.float64)[:, None]
        with np.errstate(invalid="ignore"):
            valid = (u >= -inside) & (v >= -inside) & (u + v <= 1.0 + inside) & (t > 0.0) & (
                t <= limit)
        t = np.where(valid, t, np.inf)
        best = np.argmin(t, axis=1)
        picked = t[np.arange(len(best)), best]
        hit = np.isfinite(picked)
        t_out[rows] = picked
        prim[rows] = np.where(hit, best, -1)
        u_out[rows] = np.where(hit, u[np.arange(len(best)), best], 0.0)
        v_out[rows] = np.where(hit, v[np.arange(len(best)), best], 0.0)
    return t_out, prim, u_out, v_out


def hit_of_triangle(vertices, faces, triangle, origins, directions):
    """(t, u, v) of each ray against its own triangle (triangle[i] for ray i, >= 0)."""
    vertices = np.asarray(vertices, np.float64)
    a = vertices[faces[triangle, 0]]
    e1 = vertices[faces[triangle, 1]] - a
    e2 = vertices[faces[triangle, 2]] - a
    d = np.asarray(directions, np.float64)
    s = np.asarray(origins, np.float64) - a
    p = np.cross(d, e2)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / np.einsum("rk,rk->r", p, e1)
        q = np.cross(s, e1)
        return (np.einsum("rk,rk->r", q, e2) * inv, np.einsum("rk,rk->r", s, p) * inv,
                np.einsum("rk,rk->r", d, q) * inv)
