"""A straightforward vectorised NumPy implementation of noncirc's three-arm model.

It computes the same quantities as the Rust core for a batch of designs (12-point
spline sun, installed sun frame, clockwise carrier, pusher on the left, three arms:
`train.arms = 3`, the paper's train), vectorised over
the designs with NumPy arrays, as a Python developer would write it:

- the periodic cubic spline by a batched dense solve;
- the closure by a vectorised safeguarded Newton iteration;
- the intermediate's turn by FFT;
- its inverse by `np.interp` on a spectrally upsampled grid;
- events at the samples (no sub-sample refinement);
- seven of the eight objectives (the seedling-push objective is left out).

`tests/test_numpy_reference.py` checks that it agrees with noncirc; `bench_numpy.py`
measures noncirc's speed-up over it.
"""

from __future__ import annotations

import numpy as np

TAU = 2.0 * np.pi


def spline(angles: np.ndarray, radii: np.ndarray):
    """Periodic cubic spline coefficients for each design: knots (B, m), h, second derivatives."""
    b, m = radii.shape
    h = np.diff(np.concatenate([angles, angles[:, :1] + TAU], axis=1), axis=1)
    a = np.zeros((b, m, m))
    idx = np.arange(m)
    a[:, idx, (idx - 1) % m] += h[:, (idx - 1) % m]
    a[:, idx, idx] += 2.0 * (h[:, (idx - 1) % m] + h)
    a[:, idx, (idx + 1) % m] += h
    nxt, prv = np.roll(radii, -1, axis=1), np.roll(radii, 1, axis=1)
    rhs = 6.0 * ((nxt - radii) / h - (radii - prv) / np.roll(h, 1, axis=1))
    second = np.linalg.solve(a, rhs[..., None])[..., 0]
    return h, second


def spline_eval(angles, radii, h, second, psi):
    """rho, rho', rho'' at psi (B, N)."""
    m = radii.shape[1]
    x = angles[:, :1] + np.mod(psi - angles[:, :1], TAU)
    seg = (x[..., None] >= angles[:, None, :]).sum(-1) - 1
    take = lambda v, s: np.take_along_axis(v, s, axis=1)  # noqa: E731
    nseg = (seg + 1) % m
    hs, r0, r1 = take(h, seg), take(radii, seg), take(radii, nseg)
    m0, m1 = take(second, seg), take(second, nseg)
    t = x - take(angles, seg)
    c1 = (r1 - r0) / hs - hs * (2.0 * m0 + m1) / 6.0
    c2, c3 = m0 / 2.0, (m1 - m0) / (6.0 * hs)
    return r0 + t * (c1 + t * (c2 + t * c3)), c1 + t * (2.0 * c2 + 3.0 * t * c3), 2.0 * c2 + 6.0 * t * c3


def closure(rho: np.ndarray, iterations: int = 60) -> np.ndarray:
    """Centre distance per design: safeguarded Newton on 1/mean(rho/(a-rho)) - 1."""
    rmin, rmax = rho.min(1), rho.max(1)
    lo, hi = np.maximum(rmax, 2 * rmin), 2 * rmax
    a = np.clip(2 * rho.mean(1), lo, hi)
    a = np.where(a <= rmax, 0.5 * (lo + hi), a)
    for _ in range(iterations):
        gap = a[:, None] - rho
        ok = (gap > 0).all(1)
        q = np.where(gap > 0, rho / np.where(gap > 0, gap, 1.0), 0.0)
        mean, dmean = q.mean(1), -(q / np.where(gap > 0, gap, 1.0)).mean(1)
        h = np.where(ok, 1.0 / mean - 1.0, -1.0)
        dh = np.where(ok, -dmean / mean**2, np.nan)
        lo = np.where(h < 0, a, lo)
        hi = np.where(h >= 0, a, hi)
        nxt = a - h / dh
        bad = ~((nxt > lo) & (nxt < hi))
        a = np.where(bad, 0.5 * (lo + hi), nxt)
    return a


def cumulative(g: np.ndarray) -> np.ndarray:
    """Spectral cumulative integral of periodic samples (B, N) on [0, 2π): drift + periodic."""
    n = g.shape[1]
    c = np.fft.rfft(g, axis=1) / n
    k = np.arange(c.shape[1])
    mean = c[:, 0].real
    p = np.zeros_like(c)
    p[:, 1:] = c[:, 1:] / (1j * k[1:])
    if n % 2 == 0:
        p[:, -1] = 0.0
    periodic = np.fft.irfft(p * n, n=n, axis=1)
    u = TAU * np.arange(n) / n
    return mean[:, None] * u + periodic - periodic[:, :1], mean


def upsample_cumulative(g: np.ndarray, factor: int):
    """Φ on a grid `factor` times finer, by zero-padding the spectrum."""
    n = g.shape[1]
    c = np.fft.rfft(g, axis=1) / n
    k = np.arange(c.shape[1])
    p = np.zeros((g.shape[0], n * factor // 2 + 1), dtype=complex)
    p[:, 1 : c.shape[1]] = c[:, 1:] / (1j * k[1:])
    if n % 2 == 0:
        p[:, c.shape[1] - 1] = 0.0
    fine = np.fft.irfft(p * n * factor, n=n * factor, axis=1)
    u = TAU * np.arange(n * factor) / (n * factor)
    return u, c[:, 0].real[:, None] * u + fine - fine[:, :1], c[:, 0].real


def evaluate(x: np.ndarray, names: list[str], base: dict, samples: int = 120, upsample: int = 16) -> dict:
    """Evaluates designs `x` (B, d) whose columns are `names`; `base` holds the rest."""
    cols = {n: x[:, i] for i, n in enumerate(names)}
    b = x.shape[0]
    radii = np.stack([cols.get(f"gear.curve.radii_mm[{i}]", np.full(b, base["radii"][i])) for i in range(12)], axis=1)
    angles = np.radians(np.tile(base["angles"], (b, 1)))
    get = lambda key: cols.get(f"train.{key}", np.full(b, base[key]))  # noqa: E731
    phi0, beta0, gamma0 = np.radians(get("phi0_deg")), np.radians(get("beta0_deg")), np.radians(get("gamma0_deg"))
    s, h1 = get("arm_length_mm"), get("pusher_offset_mm")
    n = samples
    theta = TAU * np.arange(n) / n
    h, second = spline(angles, radii)
    # Clockwise carrier, sun installed at Φ0: the contact sits at ψ = −θ on the sun.
    psi = np.tile(-theta, (b, 1))
    rho, d1, d2 = spline_eval(angles, radii, h, second, psi)
    a = closure(rho)
    g = rho / (a[:, None] - rho)
    u, big_phi, drift = upsample_cumulative(g, upsample)
    delay = np.mod(-(gamma0 - np.pi), TAU)
    target = big_phi[:, ::upsample] - delay[:, None]
    period = drift * TAU
    theta_s = np.empty((b, n))
    for i in range(b):  # np.interp is one-dimensional: one design at a time
        turns = np.floor(target[i] / period[i])
        rest = target[i] - turns * period[i]
        grid = np.append(big_phi[i], period[i])
        theta_s[i] = np.interp(rest, grid, np.append(u, TAU)) + turns * TAU
    theta3 = phi0[:, None] - (theta - theta_s) + gamma0[:, None] + np.pi
    phi_h = phi0[:, None] - theta
    o3x = a[:, None] * (np.cos(phi_h) + np.cos(phi_h + gamma0[:, None]))
    o3y = a[:, None] * (np.sin(phi_h) + np.sin(phi_h + gamma0[:, None]))
    dx = o3x + s[:, None] * np.cos(theta3 + beta0[:, None])
    dy = o3y + s[:, None] * np.sin(theta3 + beta0[:, None])
    pusher = theta3 + beta0[:, None] + np.arcsin(h1 / s)[:, None]
    attitude = np.degrees(np.arcsin(np.clip(-np.sin(pusher), -1, 1)))
    normal = np.radians(base["tray_normal_deg"])
    jp = np.argmax(dx * np.cos(normal) + dy * np.sin(normal), axis=1)
    jl = np.argmin(dy, axis=1)
    rows = np.arange(b)
    picking, pushing = attitude[rows, jp], attitude[rows, jl]
    height = dy.max(1) - dy.min(1)
    rmin, rmax = rho.min(1), rho.max(1)
    housing = np.maximum.reduce([rmax, 2 * a - rmin, 2 * a * np.abs(np.cos(gamma0 / 2)) + rmax]) + base["housing_margin_mm"]
    ground = -housing - (dy.min(1) + base["planting_depth_mm"])
    # Module: least convex / concave curvature radius of the sun and its conjugate.
    gap = a[:, None] - rho
    q = -d1 * gap / rho
    dq = -d2 * gap / rho + d1**2 / rho + d1**2 * gap / rho**2
    conj = (gap, q, dq * gap / rho)

    def kappa(r, r1, r2):
        s2 = r * r + r1 * r1
        return (r * r + 2 * r1 * r1 - r * r2) / (s2 * np.sqrt(s2))

    ks = np.concatenate([kappa(rho, d1, d2), kappa(*conj)], axis=1)
    convex = 1.0 / np.where(ks > 0, ks, 0).max(1)
    concave = np.where((ks < 0).any(1), -1.0 / np.where(ks < 0, ks, 0).min(1), np.inf)
    perimeter = np.sqrt(rho**2 + d1**2).sum(1) * TAU / n
    limit = np.minimum(2 * convex / base["z_min"], 2 * concave / base["cutter_teeth"])
    teeth = np.maximum(np.ceil(perimeter / (np.pi * limit) - 1e-9), 1)
    module = perimeter / (np.pi * teeth)
    # Interference: arm I against arm II (capsules) and planets II, III (discs).
    k2 = (np.arange(n) - n // 3) % n
    k3 = (np.arange(n) - 2 * n // 3) % n
    p0, p1 = np.stack([o3x, o3y], -1), np.stack([dx, dy], -1)

    def point_segment(p, s0, s1):
        ab, ap = s1 - s0, p - s0
        t = np.clip((ap * ab).sum(-1) / np.maximum((ab * ab).sum(-1), 1e-300), 0, 1)
        return np.linalg.norm(ap - t[..., None] * ab, axis=-1)

    q0, q1 = p0[:, k2], p1[:, k2]
    seg = np.minimum.reduce(
        [point_segment(p0, q0, q1), point_segment(p1, q0, q1), point_segment(q0, p0, p1), point_segment(q1, p0, p1)]
    )
    cross = lambda u, v: u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]  # noqa: E731
    r_, s_, d_ = p1 - p0, q1 - q0, q0 - p0
    den = cross(r_, s_)
    with np.errstate(divide="ignore", invalid="ignore"):
        tt, uu = cross(d_, s_) / den, cross(d_, r_) / den
    seg = np.where((den != 0) & (tt >= 0) & (tt <= 1) & (uu >= 0) & (uu <= 1), 0.0, seg)
    w = base["arm_half_width_mm"]
    planets = np.minimum(point_segment(p0[:, k2], p0, p1), point_segment(p0[:, k3], p0, p1)) - rmax[:, None] - w
    interference = np.minimum(seg - 2 * w, planets).min(1)
    return {
        "centre_distance_mm": a,
        "trajectory": np.stack([dx, dy], -1),
        "interference": interference,
        "picking_angle": picking,
        "pushing_angle": pushing,
        "angle_difference": pushing - picking,
        "ground_clearance": ground,
        "trajectory_height": height,
        "module": module,
    }


PAPER = {
    "radii": [21, 28, 50, 49, 58, 47, 18, 12, 28, 60, 48, 24],
    "angles": [20, 45, 76, 105, 132, 165, 195, 225, 255, 285, 316, 345],
    "phi0_deg": 86.0,
    "beta0_deg": -29.0,
    "arm_length_mm": 145.0,
    "pusher_offset_mm": 65.0,
    "gamma0_deg": -53.0,
    "tray_normal_deg": -10.0,
    "housing_margin_mm": 10.0,
    "planting_depth_mm": 25.0,
    "arm_half_width_mm": 12.0,
    "z_min": 17.0,
    "cutter_teeth": 12.0,
}
