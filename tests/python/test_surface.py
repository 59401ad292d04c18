"""tribo.surface and periodic contact from Python: the generator against the Rust library
(stored checksums), statistics against the closed forms of sinusoids, Westergaard's periodic
wavy contact, the X3P fixtures of tribo-case's tests, bad input, and (opt-in, where the
package `tamaas` is installed) the same periodic solve in Tamaas."""

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tribo
from tribo import surface

ROOT = Path(__file__).resolve().parents[2]
FIXTURES = ROOT / "crates" / "tribo-case" / "tests" / "data" / "topography"


def fnv1a(heights: np.ndarray) -> int:
    """FNV-1a (64 bits) of the little-endian bytes of the heights in C order (x fastest): the
    checksum of crates/tribo/tests/surface_checksum.rs."""
    h = 0xCBF29CE484222325
    for b in np.ascontiguousarray(heights, dtype="<f8").tobytes():
        h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def checksum_params(method, seed):
    """The parameters of crates/tribo/tests/surface_checksum.rs::params."""
    return dict(shape=(32, 48), size=(1.5e-3, 1.0e-3), hurst=0.7,
                rolloff=2 * math.pi / 0.5e-3, powerlaw_start=2 * math.pi / 0.25e-3,
                cutoff=2 * math.pi / 0.1e-3, anisotropy=(1.0, 1.5), rms_slope=0.05,
                method=method, seed=seed)


# The constants of crates/tribo/tests/surface_checksum.rs (the Rust library's own surfaces).
FILTER_CHECKSUM = 0x51CA212CACA28DC4
RANDOM_PHASE_CHECKSUM = 0x92B7DCF826A0FF73


def test_same_seed_same_surface_as_the_rust_library():
    f = surface.self_affine(**checksum_params("filter", 12345))
    p = surface.self_affine(**checksum_params("random_phase", 7))
    assert f.shape == (32, 48) and f.spacing == pytest.approx((31.25e-6, 31.25e-6), rel=1e-15)
    assert f.size == pytest.approx((1.5e-3, 1.0e-3), rel=1e-15)
    assert fnv1a(f.heights) == FILTER_CHECKSUM
    assert fnv1a(p.heights) == RANDOM_PHASE_CHECKSUM
    # Another seed, another surface; the same seed again, the same bits.
    again = surface.self_affine(**checksum_params("filter", 12345))
    assert np.array_equal(again.heights, f.heights)
    other = surface.self_affine(**checksum_params("filter", 12346))
    assert not np.array_equal(other.heights, f.heights)


def two_sinusoids(nx=64, ny=48, kx=3, ky=5, a=2e-6, b=1e-6, lx=2e-3, ly=1.5e-3):
    """h = a cos(2 pi kx x / Lx) + b sin(2 pi ky y / Ly) on nx x ny points (one period)."""
    x = np.arange(nx) * lx / nx
    y = np.arange(ny) * ly / ny
    X, Y = np.meshgrid(x, y)
    qx, qy = 2 * math.pi * kx / lx, 2 * math.pi * ky / ly
    h = a * np.cos(qx * X) + b * np.sin(qy * Y)
    return surface.Topography(h, (lx / nx, ly / ny)), qx, qy


def test_statistics_of_two_sinusoids_against_closed_forms():
    # Every statistic of a trigonometric polynomial on whole periods is exact up to round-off
    # (the FFT's ~1e-15 relative): tolerance 1e-12.
    a, b = 2e-6, 1e-6
    t, qx, qy = two_sinusoids(a=a, b=b)
    m = surface.moments(t)
    exact = dict(m00=(a * a + b * b) / 2, m20=a * a * qx**2 / 2, m02=b * b * qy**2 / 2,
                 m40=a * a * qx**4 / 2, m04=b * b * qy**4 / 2, m22=0.0, m11=0.0)
    for k, v in exact.items():
        assert m[k] == pytest.approx(v, rel=1e-12, abs=1e-12 * m["m00"] * qx**4), k
    assert surface.rms_heights(t) == pytest.approx(math.sqrt((a * a + b * b) / 2), rel=1e-12)
    slope = math.sqrt((a * qx) ** 2 / 2 + (b * qy) ** 2 / 2)
    assert surface.rms_slopes(t) == pytest.approx(slope, rel=1e-12)
    # Forward differences see each mode through 2 sin(q d / 2) / d (docs/theory/SURFACES.md 3).
    dx, dy = t.spacing
    fx, fy = 2 * math.sin(qx * dx / 2) / dx, 2 * math.sin(qy * dy / 2) / dy
    fd = math.sqrt((a * fx) ** 2 / 2 + (b * fy) ** 2 / 2)
    assert surface.rms_slopes(t, method="fd") == pytest.approx(fd, rel=1e-12)
    assert surface.rms_slopes(t, method="fd") < surface.rms_slopes(t)
    # Mean curvature (h_xx + h_yy)/2: rms sqrt((m40 + 2 m22 + m04) / 4).
    curv = math.sqrt((a * a * qx**4 / 2 + b * b * qy**4 / 2) / 4)
    assert surface.rms_curvature(t) == pytest.approx(curv, rel=1e-12)
    # A bare array with its spacing gives the same.
    assert surface.rms_slopes(t.heights, t.spacing) == surface.rms_slopes(t)


def test_psd_and_autocorrelation_of_a_sinusoid():
    # h = a cos(q x), q = 2 pi 6 / L on a square period: the PSD's power sits in the bin of
    # |q| = q (Parseval: sum C dq^2 over modes = a^2 / 2, to round-off) and the
    # autocorrelation is (a^2 / 2) cos(q r_x), independent of r_y.
    n, L, a, k = 64, 1e-3, 1e-6, 6
    x = np.arange(n) * L / n
    h = np.tile(a * np.cos(2 * math.pi * k * x / L), (n, 1))
    t = surface.Topography(h, (L / n, L / n))
    s = surface.psd(t)
    dq2 = (2 * math.pi / L) ** 2
    total = float(np.sum(s.psd * s.modes) * dq2)
    assert total == pytest.approx(a * a / 2, rel=1e-12)
    # The peak bin is the annulus of |q| = 2 pi k / L: its mean |q| (over all its modes, most
    # without power) within half the bin width 2 pi / L of it.
    peak = int(np.argmax(s.psd))
    assert abs(s.q[peak] - 2 * math.pi * k / L) <= 0.5 * 2 * math.pi / L
    assert s.psd[peak] * s.modes[peak] * dq2 == pytest.approx(a * a / 2, rel=1e-12)
    r = surface.autocorrelation(t)
    assert r.shape == (n, n)
    expected = (a * a / 2) * np.cos(2 * math.pi * k * x / L)
    np.testing.assert_allclose(r, np.tile(expected, (n, 1)), rtol=0, atol=1e-12 * a * a)


def test_generated_statistics_against_the_spectrum():
    # Random phases carry the spectrum's discrete moments exactly (docs/theory/SURFACES.md 2):
    # the rms slope equals its target, and the rms height and curvature the spectrum's moments
    # scaled by the same plateau, to round-off (1e-11). The Hurst exponent fitted to the
    # radial PSD over the power law: within 0.02 (the Rust tests reach 0.01 at 256^2; at 128^2
    # the annuli near the cutoff hold fewer modes and the jump at q_s weighs more).
    spec = dict(hurst=0.8, powerlaw_start=2 * math.pi * 4 / 1e-3,
                cutoff=2 * math.pi * 32 / 1e-3)
    t = surface.self_affine(128, size=1e-3, rms_slope=0.2, method="random_phase", seed=3,
                            **spec)
    assert surface.rms_slopes(t) == pytest.approx(0.2, rel=1e-11)
    d = surface.spectrum_moments(shape=t.shape, size=t.size, **spec)["discrete"]
    plateau = 0.2**2 / d["rms_slope"] ** 2
    assert surface.rms_heights(t) == pytest.approx(d["rms_height"] * math.sqrt(plateau),
                                                   rel=1e-11)
    assert surface.rms_curvature(t) == pytest.approx(d["rms_curvature"] * math.sqrt(plateau),
                                                     rel=1e-11)
    fit = surface.psd(t).fit(spec["powerlaw_start"] * 1.5, spec["cutoff"] * 0.9)
    assert fit.hurst == pytest.approx(0.8, abs=0.02)
    # The continuous moments (closed forms) and the discrete sums over a 128^2 grid agree to
    # the first-order quadrature error of the jumps at q_r and q_s, largest for m00 (its
    # weight sits at q_r, 8 dq here): measured 3.5 %, 0.64 %, 0.37 % for m00, m20, m40;
    # bounds 5 %, 1.5 %, 1.5 % (a wrong factor 2 pi or Jacobian is off by far more).
    spec = dict(hurst=0.8, powerlaw_start=2 * math.pi * 8 / 1e-3,
                cutoff=2 * math.pi * 48 / 1e-3)
    m = surface.spectrum_moments(shape=(128, 128), size=(1e-3, 1e-3), **spec)
    for key, bound in (("m00", 0.05), ("m20", 0.015), ("m40", 0.015)):
        assert m["discrete"][key] == pytest.approx(m["continuous"][key], rel=bound), key


def test_filtered_noise_rms_within_its_sampling_error():
    # Filtered white noise: the squared rms height fluctuates about the spectrum's discrete
    # m00 with the standard deviation of docs/theory/SURFACES.md 3; one surface lies within
    # 4 standard deviations (a false failure once in ~15 000 seeds; this seed is fixed).
    spec = dict(hurst=0.6, powerlaw_start=2 * math.pi * 2 / 1e-3,
                cutoff=2 * math.pi * 40 / 1e-3)
    t = surface.self_affine((96, 128), size=(1e-3 * 128 / 96, 1e-3), rms_height=1e-6,
                            seed=11, **spec)
    m = surface.spectrum_moments(shape=t.shape, size=t.size, **spec)
    ratio = (1e-6) ** 2 / m["discrete"]["m00"]
    std = m["discrete_std"]["m00"] * ratio
    assert abs(surface.rms_heights(t) ** 2 - 1e-12) < 4 * std


def test_tamaas_like_generator():
    # Isopowerlaw + SurfaceGeneratorRandomPhase at Tamaas's level: E|h_q|^2 = Phi(q) with
    # Phi = 1 on the plateau, so the random-phase surface's variance is sum_q Phi(q) exactly
    # (1e-11): counted here directly from the shape at the integer wavenumbers.
    spectrum = surface.Isopowerlaw(q0=2, q1=4, q2=16, hurst=0.8)
    gen = surface.SurfaceGeneratorRandomPhase((64, 64))
    gen.spectrum = spectrum
    gen.random_seed = 5
    h = gen.buildSurface()
    assert isinstance(h, np.ndarray) and h.shape == (64, 64)
    k = np.fft.fftfreq(64, 1 / 64)
    K = np.hypot(*np.meshgrid(k, k))
    phi = np.where((K >= 2) & (K < 4), 1.0, 0.0) + np.where(
        (K >= 4) & (K <= 16), (np.maximum(K, 4) / 4) ** (-2 * 1.8), 0.0)
    assert float(np.mean(h**2)) == pytest.approx(float(phi.sum()), rel=1e-11)
    # The filter generator with the same spectrum is the "filter" method of self_affine.
    f = surface.SurfaceGeneratorFilter((64, 64))
    f.spectrum, f.random_seed, f.rms_slope = spectrum, 9, 0.3
    t = f.build()
    same = surface.self_affine((64, 64), size=(1.0, 1.0), hurst=0.8, rolloff=2 * math.pi * 2,
                               powerlaw_start=2 * math.pi * 4, cutoff=2 * math.pi * 16,
                               rms_slope=0.3, seed=9)
    assert np.array_equal(t.heights, same.heights)
    # Errors name Tamaas's attributes.
    f.spectrum = surface.Isopowerlaw(q0=2, q1=4, q2=3, hurst=0.8)
    with pytest.raises(tribo.InputError) as e:
        f.build()
    assert e.value.field == "spectrum.q2"


def test_detrend_and_resample():
    # A plane (degree 1) and a quadric (degree 2) are removed to round-off.
    n, L = 40, 1e-3
    x = np.arange(n) * L / n
    X, Y = np.meshgrid(x, x)
    plane = 1e-6 + 2e-3 * X - 1e-3 * Y
    t = surface.Topography(plane, (L / n, L / n))
    assert np.abs(surface.detrend(t).heights).max() < 1e-12 * np.abs(plane).max()
    quad = plane + 3.0 * (X - L / 2) ** 2 + 1.0 * X * Y
    r = surface.detrend(surface.Topography(quad, (L / n, L / n)), degree=2)
    assert np.abs(r.heights).max() < 1e-12 * np.abs(quad).max()
    # Keys' interpolant passes through the points: resampling at a quarter of the spacing
    # returns the original points exactly at every fourth index; between them the error of a
    # sinusoid falls by ~8 per halving of the spacing (third order; measured 8.25 from 16 to
    # 32 points per wavelength; at the midpoints alone it is fourth order, 15.6): the ratio
    # lies in [6, 10] (a linear interpolant gives 4, a C0 cubic or a wrong stencil less).
    def error(points_per_wavelength):
        m = 4 * points_per_wavelength
        xs = np.arange(m) * L / m
        h = np.tile(1e-6 * np.sin(2 * math.pi * 4 * xs / L), (4, 1))
        t = surface.Topography(h, (L / m, L / m))
        fine = surface.resample(t, (4, 4 * m), (L / (4 * m), L / m))
        assert np.array_equal(fine.heights[:, ::4], h)
        xf = np.arange(4 * m) * L / (4 * m)
        return np.abs(fine.heights[0] - 1e-6 * np.sin(2 * math.pi * 4 * xf / L)).max()

    ratio = error(16) / error(32)
    assert 6 < ratio < 10


def westergaard(nx, p_ratio, kernel):
    """Westergaard's wavy surface h = D (1 - cos(2 pi x / lam)) on nx x 4 elements over one
    wavelength, at p_mean = p_ratio p* (p* = pi E* D / lam)."""
    lam, D, E = 1e-3, 1e-6, 1e11
    dx = lam / nx
    x = -lam / 2 + (np.arange(nx) + 0.5) * dx
    h = np.tile(D * (1 - np.cos(2 * math.pi * x / lam)), (4, 1))
    p_star = math.pi * E * D / lam
    r = tribo.normal_contact(h, size=(lam, 4 * dx), composite_modulus=E,
                             mean_pressure=p_ratio * p_star, periodic=True, kernel=kernel)
    return r, x, lam, p_star


@pytest.mark.parametrize("kernel", ["element", "spectral"])
@pytest.mark.parametrize("p_ratio", [0.5, 0.2])
def test_westergaard_periodic_contact(kernel, p_ratio):
    # Westergaard 1939 (Johnson 1985 sec. 13.2): p_mean = p* sin^2(pi a / lam), and
    # p(x) = 2 p_mean cos(pi x/lam) sqrt(sin^2(pi a/lam) - sin^2(pi x/lam)) / sin^2(pi a/lam).
    # On 255 elements per wavelength: the half-width counted in elements within one element
    # (1.6 % of lam/4 at p*/2); the L1 pressure error, O(h^1.5) from the square-root edges
    # (crates/tribo/src/validation/periodic.rs), measured 1.2e-4 (p*/2) and 2.7e-4 (0.2 p*)
    # with the element kernel, 1.3e-4 and 1.6e-4 with the spectral one: bound 5e-4 (a wrong
    # factor 2 in the compliance moves a by 20 %, the L1 error to ~1e-1).
    nx = 255
    r, x, lam, p_star = westergaard(nx, p_ratio, kernel)
    p_mean = p_ratio * p_star
    assert r.periodic and r.mean_pressure == pytest.approx(p_mean, rel=1e-12)
    assert r.residual < 1e-10
    sa2 = p_ratio
    a_exact = lam / math.pi * math.asin(math.sqrt(sa2))
    row = r.pressure[0]
    np.testing.assert_array_equal(r.pressure, np.tile(row, (4, 1)))
    a = 0.5 * np.count_nonzero(row) * (lam / nx)
    assert abs(a - a_exact) <= lam / nx
    sx2 = np.sin(math.pi * x / lam) ** 2
    exact = np.where(sx2 < sa2, 2 * p_mean * np.cos(math.pi * x / lam)
                     * np.sqrt(np.maximum(sa2 - sx2, 0.0)) / sa2, 0.0)
    l1 = np.abs(row - exact).sum() / np.abs(exact).sum()
    assert l1 < 5e-4
    # The mask, the gap (0 in contact) and the displacement (g - h + delta, zero mean).
    assert r.contact_fraction == pytest.approx(2 * a / lam, rel=1e-12)
    assert np.abs(r.gap[r.contact]).max() < 1e-10 * 1e-6
    assert abs(float(r.displacement.mean())) < 1e-9 * np.abs(r.displacement).max()


def test_westergaard_half_width_converges_with_the_grid():
    # The half-width counted in elements approaches a = lam/4 at p*/2 as 1/nx: the error at
    # 511 elements is at most one element, and no larger than at 127.
    errs = []
    for nx in (127, 511):
        r, _, lam, _ = westergaard(nx, 0.5, "element")
        a = 0.5 * np.count_nonzero(r.pressure[0]) * lam / nx
        errs.append(abs(a - lam / 4))
        assert errs[-1] <= lam / nx
    assert errs[1] <= errs[0]


def test_periodic_rough_contact_and_solver_reuse():
    # A rough flat on a flat: the contact reaches the window's border (refused without
    # periodic=True), the force is the mean pressure times the period area, and the reused
    # periodic solver (a load path with warm starts) gives the same solution to the
    # tolerance. The real contact fraction grows with the load.
    t = surface.self_affine(64, size=1e-3, hurst=0.8, powerlaw_start=2 * math.pi * 4 / 1e-3,
                            cutoff=2 * math.pi * 16 / 1e-3, rms_slope=0.05, seed=2)
    E = 1e11
    with pytest.raises(tribo.InputError):
        tribo.normal_contact(t.gap(), size=t.size, composite_modulus=E, load=1e-3 * 1e6)
    r = tribo.normal_contact(t.gap(), size=t.size, composite_modulus=E, mean_pressure=2e8,
                             periodic=True)
    assert r.normal_load == pytest.approx(2e8 * 1e-6, rel=1e-12)
    assert 0 < r.contact_fraction < 1
    border = np.concatenate([r.pressure[0], r.pressure[-1], r.pressure[:, 0], r.pressure[:, -1]])
    assert (border > 0).any()
    solver = tribo.NormalSolver(t.shape, size=t.size, composite_modulus=E, periodic=True)
    path = list(solver.load_path(t.gap(), mean_pressures=[1e8, 2e8]))
    np.testing.assert_allclose(path[1].pressure, r.pressure, rtol=0,
                               atol=1e-7 * r.max_pressure)
    assert path[0].contact_fraction < path[1].contact_fraction


def test_periodic_tangential_sliding_and_partial_slip():
    # On the periodic Westergaard pressure: full sliding gives q = f p exactly, and a partial
    # slip load below f F_N gives the force per period, |q| <= f p, and a stick zone inside
    # the contact (parallel and free directions, element and spectral kernels).
    r, _, lam, _ = westergaard(127, 0.5, "element")
    f, E, nu = 0.3, 2.1e11, 0.3
    s = tribo.tangential_contact(r.pressure, size=r.size, friction=f, E1=E, nu1=nu, E2=E,
                                 nu2=nu, sliding=True, periodic=True)
    np.testing.assert_allclose(s.traction_x, f * r.pressure, rtol=1e-14, atol=0)
    Q = 0.5 * f * r.normal_load
    for direction in ("parallel", "free"):
        for kernel in ("element", "spectral"):
            t = tribo.tangential_contact(r.pressure, size=r.size, friction=f, E1=E, nu1=nu,
                                         E2=E, nu2=nu, tangential_load=Q, periodic=True,
                                         kernel=kernel, direction=direction)
            assert t.tangential_force[0] == pytest.approx(Q, rel=1e-8)
            q = np.hypot(t.traction_x, t.traction_y)
            assert (q <= f * r.pressure * (1 + 1e-9) + 1e-9 * f * r.max_pressure).all()
            assert t.stick_area > 0 and t.slip_area > 0


def test_read_the_x3p_fixtures():
    # The fixtures of crates/tribo-case/src/topography/tests.rs: 5 x 4 points,
    # h(i, j) = 1e-7 (i + 10 j) + 1e-8 i j (m), dx = 0.5 um, dy = 0.25 um; float32 data
    # within the float32 round-off (1.2e-7 of 4e-6 m), int32 counts of 0.1 nm within 0.05 nm.
    i, j = np.meshgrid(np.arange(5), np.arange(4))
    exact = 1e-7 * (i + 10 * j) + 1e-8 * i * j
    for name, tol in (("grid_f.x3p", 4e-6 * 1.2e-7), ("grid_l.x3p", 0.5e-10 + 1e-20)):
        t = surface.read(FIXTURES / name)
        assert t.shape == (4, 5) and t.invalid == 0
        assert t.spacing == pytest.approx((0.5e-6, 0.25e-6), rel=1e-12)
        np.testing.assert_allclose(t.heights, exact, rtol=0, atol=tol)
        assert t.path.endswith(name)
    # Invalid points: refused by default, naming the file and the point; kept as NaN on demand.
    with pytest.raises(tribo.InputError) as e:
        surface.read(FIXTURES / "grid_d.x3p")
    assert e.value.field == "path" and "grid_d.x3p" in str(e.value) and "invalid" in str(e.value)
    t = surface.read(FIXTURES / "grid_d.x3p", keep_invalid=True)
    assert t.invalid == 1 and math.isnan(t.heights[1, 2])
    with pytest.raises(tribo.InputError):
        surface.rms_heights(t)
    # npy needs the spacing; the height unit scales.
    with pytest.raises(tribo.InputError) as e:
        surface.read(FIXTURES / "c_f8.npy")
    assert "spacing" in str(e.value) and "c_f8.npy" in str(e.value)
    t = surface.read(FIXTURES / "c_f8.npy", spacing=(0.5e-6, 0.25e-6))
    np.testing.assert_allclose(t.heights, exact, rtol=0, atol=1e-22)
    t = surface.read(FIXTURES / "c_i4_nm.npy", spacing=(0.5e-6, 0.25e-6), height_unit=1e-9)
    np.testing.assert_allclose(t.heights, exact, rtol=0, atol=1e-20)
    # ASCII grids: tribo's header (spacing in um and nm, heights in um) and Gwyddion's export
    # header (the real size and the value unit), both carrying the spacing.
    for name, tol in (("tribo_header.txt", 1e-20), ("gwyddion.txt", 1e-22)):
        t = surface.read(FIXTURES / name)
        assert t.spacing == pytest.approx((0.5e-6, 0.25e-6), rel=1e-12), name
        np.testing.assert_allclose(t.heights, exact, rtol=0, atol=tol)


@pytest.mark.parametrize("name, needle", [("truncated.x3p", "not a readable X3P archive"),
                                          ("profile.x3p", "FeatureType = PRF"),
                                          ("make_fixtures.py", "unknown topography format"),
                                          ("missing.x3p", "cannot read")])
def test_bad_files_name_the_file_and_the_problem(name, needle):
    with pytest.raises(tribo.InputError) as e:
        surface.read(FIXTURES / name)
    assert e.value.field == "path" and name in str(e.value) and needle in str(e.value)


GOOD = dict(shape=(32, 32), size=1e-3, hurst=0.8, powerlaw_start=2e4, cutoff=1e5,
            rms_height=1e-6)


@pytest.mark.parametrize("change, field", [
    (dict(hurst=1.5), "hurst"),
    (dict(hurst=0.0), "hurst"),
    (dict(cutoff=1e4), "cutoff"),
    (dict(rolloff=3e4), "powerlaw_start"),
    (dict(rms_slope=0.1), "rms_height"),
    (dict(rms_height=-1.0), "rms_height"),
    (dict(shape=(1, 32)), "shape"),
    (dict(shape=(2**31, 2**31)), "shape"),
    (dict(shape=(2**20, 2**20)), "shape"),
    (dict(size=(1e-3, -1.0)), "size"),
    (dict(method="gauss"), "method"),
    (dict(anisotropy=(1.0, 0.0)), "anisotropy[1]"),
    (dict(seed=-1), "seed"),
    # Wrong types and non-integers are refused naming the argument, never truncated.
    (dict(seed=0.5), "seed"),
    (dict(seed=float("nan")), "seed"),
    (dict(seed=2**64), "seed"),
    (dict(shape=(64.5, 64)), "shape"),
    (dict(shape=(64, 64, 1)), "shape"),
    (dict(hurst="x"), "hurst"),
    (dict(cutoff=None), "cutoff"),
    (dict(rms_height=[1e-6]), "rms_height"),
    (dict(method=1), "method"),
    (dict(cutoff=1e9, powerlaw_start=5e8), "spectrum"),
])
def test_bad_generator_input_names_the_argument(change, field):
    with pytest.raises(tribo.InputError) as e:
        surface.self_affine(**{**GOOD, **change})
    assert e.value.field == field, str(e.value)


def test_bad_statistics_and_contact_input():
    h = np.zeros((8, 8))
    with pytest.raises(tribo.InputError) as e:
        surface.rms_slopes(h)
    assert e.value.field == "spacing"
    with pytest.raises(tribo.InputError) as e:
        surface.moments(h, (1e-6, -1.0))
    assert e.value.field == "spacing"
    bad = h.copy()
    bad[2, 3] = np.nan
    with pytest.raises(tribo.InputError) as e:
        surface.moments(bad, (1e-6, 1e-6))
    assert e.value.field.startswith("heights") and "row 2, column 3" in e.value.field
    with pytest.raises(tribo.InputError) as e:
        surface.rms_slopes(h, (1e-6, 1e-6), method="central")
    assert e.value.field == "method"
    with pytest.raises(tribo.InputError) as e:
        surface.detrend(surface.Topography(h, (1e-6, 1e-6)), degree=11)
    assert e.value.field == "degree"
    with pytest.raises(tribo.InputError) as e:
        surface.psd(surface.Topography(h + np.arange(8), (1e-6, 1e-6))).fit(1e9, 2e9)
    assert e.value.field == "q_range"
    gap = np.tile(np.linspace(0.0, 1e-6, 16), (16, 1))
    common = dict(size=(1e-3, 1e-3), composite_modulus=1e11)
    for kwargs, field in ((dict(approach=1e-7, periodic=True), "approach"),
                          (dict(load=1.0, periodic=True, method="active_set"), "method"),
                          (dict(load=1.0, periodic=True, kernel="fourier"), "kernel"),
                          (dict(mean_pressure=1e6), "mean_pressure"),
                          (dict(mean_pressure=1e6, load=1.0, periodic=True), "mean_pressure")):
        with pytest.raises(tribo.InputError) as e:
            tribo.normal_contact(gap, **common, **kwargs)
        assert e.value.field == field, kwargs
    with pytest.raises(tribo.InputError) as e:
        tribo.NormalSolver((16, 16), **common, periodic=True).solve(gap, approach=1e-7)
    assert e.value.field == "approach"


def test_same_periodic_solution_as_tamaas():
    # Opt-in: with the package tamaas installed (PyPI `tamaas`), the same surface loaded in
    # Tamaas's PolonskyKeerRey (periodic, the continuous kernel 2 / (E* |q|)) and in tribo with
    # kernel="spectral" gives the same pressure: both solve one discrete LCP (tolerances 1e-12
    # and 1e-10 on their residuals): measured 1.3e-10 of the peak, bound 1e-8 (the element
    # kernel, another discretisation, differs by 2.8e-2); the case at 64^2: Hurst
    # 0.8, rms slope 1, mean pressure 0.1 E*.
    tm = pytest.importorskip("tamaas")
    n = 64
    t = surface.self_affine(n, size=1.0, hurst=0.8, rolloff=2 * math.pi * 4,
                            powerlaw_start=2 * math.pi * 4, cutoff=2 * math.pi * 16,
                            rms_slope=1.0, seed=4)
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = 1.0, 0.0
    solver = tm.PolonskyKeerRey(model, np.ascontiguousarray(t.heights), 1e-12)
    solver.solve(0.1)
    p_tamaas = np.array(model.traction).reshape(n, n)
    r = tribo.normal_contact(t.gap(), size=t.size, composite_modulus=1.0, mean_pressure=0.1,
                             periodic=True, kernel="spectral", tolerance=1e-10)
    assert np.abs(r.pressure - p_tamaas).max() < 1e-8 * p_tamaas.max()
    np.testing.assert_array_equal(r.contact, p_tamaas > 0)


def test_rough_contact_example_runs():
    out = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "rough_contact.py")],
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    assert "Hurst from the PSD" in out.stdout and out.stdout.count("contact fraction") == 4


def test_surface_api_is_documented():
    for name in surface.__all__:
        obj = getattr(surface, name)
        assert obj.__doc__ and obj.__doc__.strip(), name
    assert "surface" in tribo.__all__
