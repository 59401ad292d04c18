"""Coupled and free-direction tangential contact on arrays; warm starts of the normal solver."""

import numpy as np
import pytest

import tribo

E, NU, R, F, L, N = 210e9, 0.3, 0.01, 100.0, 1e-3, 64
x = (np.arange(N) + 0.5) * L / N - L / 2
X, Y = np.meshgrid(x, x)
GAP = (X**2 + Y**2) / (2 * R)


def test_free_direction_partial_slip():
    # The free-direction solver on the same problem as the load-parallel one: the force is
    # met exactly, Coulomb's law holds, and the stick zone is Cattaneo-Mindlin's to the grid's
    # resolution. The traction's direction is free, so a small q_y appears in the slip zone:
    # measured |q_y| up to 5 % of |q_x|, Q_y = 1e-18 N by symmetry, the same stick area as the
    # parallel solver's on this grid; 4 % on the stick radius fails a wrong stick zone.
    n = tribo.normal_contact(GAP, size=(L, L), composite_modulus=tribo.composite_modulus(
        E, NU, E, NU), load=F)
    f, q = 0.3, 15.0
    kw = dict(size=(L, L), friction=f, E1=E, nu1=NU, E2=E, nu2=NU, tangential_load=q)
    par = tribo.tangential_contact(n.pressure, **kw)
    free = tribo.tangential_contact(n.pressure, direction="free", **kw)
    assert free.tangential_force[0] == pytest.approx(q, rel=1e-8)
    assert abs(free.tangential_force[1]) < 1e-6 * q
    qn = np.hypot(free.traction_x, free.traction_y)
    assert (qn <= f * n.pressure * (1 + 1e-6) + 1e-6 * f * n.max_pressure).all()
    # The traction is not parallel to the load everywhere (some q_y), unlike the parallel one.
    assert np.abs(free.traction_y).max() > 0 and np.abs(par.traction_y).max() == 0
    c_par, c_free = np.sqrt(par.stick_area / np.pi), np.sqrt(free.stick_area / np.pi)
    assert c_free == pytest.approx(c_par, rel=0.04)
    with pytest.raises(tribo.InputError) as err:
        tribo.tangential_contact(n.pressure, direction="sideways", **kw)
    assert err.value.field == "direction"


def test_coupled_contact_of_dissimilar_bodies():
    # Steel (210 GPa, 0.3) on aluminium (70 GPa, 0.33): Dundurs' beta (Johnson 1985 eq.
    # (5.4b)) in closed form; the alternation converges to its tolerance; the coupling
    # leaves the load and tangential force as prescribed.
    E2, NU2 = 70e9, 0.33
    f, q = 0.3, 15.0
    c = tribo.coupled_contact(GAP, size=(L, L), friction=f, E1=E, nu1=NU, E2=E2, nu2=NU2,
                              load=F, tangential_load=q)
    G1, G2 = E / (2 * (1 + NU)), E2 / (2 * (1 + NU2))
    beta = 0.5 * ((1 - 2 * NU) / G1 - (1 - 2 * NU2) / G2) / ((1 - NU) / G1 + (1 - NU2) / G2)
    assert abs(c.beta) == pytest.approx(abs(beta), rel=1e-12)
    assert c.passes > 1 and c.change <= 1e-8
    assert c.normal.normal_load == pytest.approx(F, rel=1e-9)
    assert c.tangential.tangential_force[0] == pytest.approx(q, rel=1e-8)
    # Similar materials: no coupling, one pass, the uncoupled solution.
    s = tribo.coupled_contact(GAP, size=(L, L), friction=f, E1=E, nu1=NU, E2=E, nu2=NU,
                              load=F, tangential_load=q)
    assert s.passes == 1 and s.beta == 0.0
    u = tribo.normal_contact(GAP, size=(L, L), composite_modulus=tribo.composite_modulus(
        E, NU, E, NU), load=F)
    np.testing.assert_allclose(s.normal.pressure, u.pressure, rtol=0,
                               atol=1e-8 * u.max_pressure)
    free = tribo.coupled_contact(GAP, size=(L, L), friction=f, E1=E, nu1=NU, E2=E2, nu2=NU2,
                                 load=F, tangential_load=q, direction="free")
    assert free.tangential.tangential_force[0] == pytest.approx(q, rel=1e-8)
    with pytest.raises(tribo.InputError):
        tribo.coupled_contact(GAP, size=(L, L), friction=f, E1=E, nu1=NU, E2=E2, nu2=NU2,
                              load=F)


def test_warm_starts_need_fewer_iterations_for_the_same_answer():
    # Both solutions meet the complementarity tolerance 1e-10 (relative to p_max), so they
    # agree to a few times that (measured 2e-9 p_max); 1e-8 p_max fails for the previous load
    # step's pressure (2 % away). Measured on this 64^2 sphere: a 2 % load step from the last
    # solution 19 iterations instead of 39; a load path in 1 % steps 16-24 instead of 33-41
    # per step (a 10 % step saves nothing: the guess's contact area is too far off).
    e_star = tribo.composite_modulus(E, NU, E, NU)
    first = tribo.normal_contact(GAP, size=(L, L), composite_modulus=e_star, load=F)
    cold = tribo.normal_contact(GAP, size=(L, L), composite_modulus=e_star, load=1.02 * F)
    warm = tribo.normal_contact(GAP, size=(L, L), composite_modulus=e_star, load=1.02 * F,
                                initial_pressure=first)
    assert warm.iterations < 0.75 * cold.iterations
    np.testing.assert_allclose(warm.pressure, cold.pressure, rtol=0,
                               atol=1e-8 * cold.max_pressure)
    assert np.abs(first.pressure - cold.pressure).max() > 1e-8 * cold.max_pressure
    # The load path warm-starts by default: fewer iterations in all, the same solutions.
    solver = tribo.NormalSolver((N, N), size=(L, L), composite_modulus=e_star)
    loads = np.linspace(90.0, 110.0, 21)
    hot = list(solver.load_path(GAP, loads=loads))
    plain = list(solver.load_path(GAP, loads=loads, warm_start=False))
    assert sum(r.iterations for r in hot[1:]) < 0.75 * sum(r.iterations for r in plain[1:])
    for a, b in zip(hot, plain):
        np.testing.assert_allclose(a.pressure, b.pressure, rtol=0, atol=1e-8 * b.max_pressure)
    with pytest.raises(tribo.InputError) as err:
        solver.solve(GAP, load=F, initial_pressure=np.ones((N, N // 2)))
    assert err.value.field == "initial_pressure"
