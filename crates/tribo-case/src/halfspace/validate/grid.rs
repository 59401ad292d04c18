//! The rules of `[grid]` (elements and window) and `[solver]`.

use crate::error::{CaseError, CaseResult};
use crate::halfspace::model::{Shape, Window, DEFAULT_EXTENT, DEFAULT_N, MAX_ACTIVE_SET_ELEMENTS};
use crate::halfspace::schema::{RawGrid, RawSolver};
use tribo::geometry::SurfaceProfile;
use tribo::grid::MAX_ELEMENTS_PER_SIDE;
use tribo::solvers::{NormalContactParams, NormalMethod};

/// Elements along x and y: 4 ... [`MAX_ELEMENTS_PER_SIDE`] each.
pub(super) fn elements(grid: &RawGrid) -> CaseResult<[usize; 2]> {
    let Some(n) = &grid.n else {
        return Ok([DEFAULT_N; 2]);
    };
    for (k, c) in n.items.iter().enumerate() {
        let f = n.item_key("grid.n", k);
        if c.n < 4 {
            return Err(CaseError::field(
                f,
                c.n,
                "at least 4 elements per side are needed",
            ));
        }
        if c.n > MAX_ELEMENTS_PER_SIDE {
            return Err(CaseError::field(
                f,
                c.n,
                format!("at most {MAX_ELEMENTS_PER_SIDE} elements per side (memory)"),
            ));
        }
    }
    Ok([n.items[0].n, n.items[1].n])
}

/// The window: `extent` (Hertzian gaps only) or `half_width`, within any height map.
pub(super) fn window(grid: &RawGrid, hertzian: bool, shapes: [&Shape; 2]) -> CaseResult<Window> {
    let window = match (&grid.extent, &grid.half_width) {
        (Some(e), Some(_)) => {
            return Err(CaseError::field(
                "grid.extent",
                e,
                "give either grid.extent or grid.half_width, not both",
            ))
        }
        (Some(e), None) => {
            if !hertzian {
                return Err(CaseError::field(
                    "grid.extent",
                    e,
                    "extent is in units of the Hertz semi-axis, defined only where both bodies \
                     are given by radii; give grid.half_width (m) for a surface",
                ));
            }
            let x = e.si();
            if !(x.is_finite() && x > 1.0) {
                return Err(CaseError::field(
                    "grid.extent",
                    e,
                    "must be a finite number > 1 (the window must contain the Hertz contact)",
                ));
            }
            Window::Extent(x)
        }
        (None, Some(h)) => {
            let hw = [h.items[0].si(), h.items[1].si()];
            for (k, w) in hw.iter().enumerate() {
                if !(w.is_finite() && *w > 0.0) {
                    return Err(CaseError::field(
                        format!("grid.half_width[{k}]"),
                        w,
                        "the window half width must be finite and > 0 (m)",
                    ));
                }
                crate::units::check_length(&format!("grid.half_width[{k}]"), &h.written, *w)?;
            }
            Window::HalfWidth(hw)
        }
        (None, None) => {
            if !hertzian {
                return Err(CaseError::field(
                    "grid.half_width",
                    "(missing)",
                    "required where a body is given by a surface (the window cannot be sized \
                     from Hertz theory): give the window half width in m, scalar or [x, y]",
                ));
            }
            Window::Extent(DEFAULT_EXTENT)
        }
    };
    if let Window::HalfWidth(hw) = window {
        for (name, s) in ["body1", "body2"].into_iter().zip(shapes) {
            if let Shape::Surface(SurfaceProfile::HeightMap(m)) = s {
                let (mx, my) = m.half_extents();
                if hw[0] > mx * (1.0 + 1e-12) || hw[1] > my * (1.0 + 1e-12) {
                    return Err(CaseError::field(
                        "grid.half_width",
                        format!("[{}, {}]", hw[0], hw[1]),
                        format!(
                            "the window must lie within the height map of {name}, which covers \
                             |x| <= {mx:e} m, |y| <= {my:e} m"
                        ),
                    ));
                }
            }
        }
    }
    Ok(window)
}

/// The window of a periodic grid (`[grid] periodic = true`): one period, `grid.period` (m)
/// or, without it, `default_period` (a measured map declared periodic); `None` for a
/// non-periodic grid (then [`window`]). A periodic grid refuses `extent` and `half_width`;
/// a non-periodic one refuses `period`.
pub(super) fn periodic_window(
    grid: &RawGrid,
    default_period: Option<[f64; 2]>,
) -> CaseResult<Option<Window>> {
    let periodic = grid.periodic.as_ref().is_some_and(|p| p.on);
    if !periodic {
        if let Some(p) = &grid.period {
            return Err(CaseError::field(
                "grid.period",
                &p.written,
                "applies to periodic grids: set grid.periodic = true, or size the window by \
                 grid.half_width",
            ));
        }
        return Ok(None);
    }
    if let Some(e) = &grid.extent {
        return Err(CaseError::field(
            "grid.extent",
            e,
            "a periodic grid is one period: size it by grid.period = [Lx, Ly] (m)",
        ));
    }
    if let Some(h) = &grid.half_width {
        return Err(CaseError::field(
            "grid.half_width",
            &h.written,
            "a periodic grid is one period: size it by grid.period = [Lx, Ly] (m)",
        ));
    }
    let period = match &grid.period {
        Some(p) => {
            let l = [p.items[0].si(), p.items[1].si()];
            for (k, w) in l.iter().enumerate() {
                let key = p.item_key("grid.period", k);
                if !(w.is_finite() && *w > 0.0) {
                    return Err(CaseError::field(
                        key,
                        w,
                        "the period must be finite and > 0 (m)",
                    ));
                }
                crate::units::check_length(&key, &p.written, *w)?;
            }
            l
        }
        None => default_period.ok_or_else(|| {
            CaseError::field(
                "grid.period",
                "(missing)",
                "required on a periodic grid: the period [Lx, Ly] (m), scalar or pair (a \
                 measured map declared periodic gives its own size)",
            )
        })?,
    };
    Ok(Some(Window::HalfWidth([0.5 * period[0], 0.5 * period[1]])))
}

/// The solver and its parameters; the dense active set only on small grids.
pub(super) fn solver(
    raw: Option<RawSolver>,
    n: [usize; 2],
    periodic: bool,
) -> CaseResult<(NormalMethod, NormalContactParams)> {
    let mut params = NormalContactParams::default();
    let Some(s) = raw else {
        return Ok((NormalMethod::ConjugateGradient, params));
    };
    let method = s
        .method
        .as_ref()
        .map_or(NormalMethod::ConjugateGradient, |m| m.value);
    if let Some(t) = &s.tolerance {
        let x = t.si();
        if !(x.is_finite() && x > 0.0 && x < 1.0) {
            return Err(CaseError::field("solver.tolerance", t, "must be in (0, 1)"));
        }
        params.tolerance = x;
    }
    if let Some(m) = &s.max_iterations {
        if m.n == 0 {
            return Err(CaseError::field(
                "solver.max_iterations",
                m.n,
                "must be at least 1",
            ));
        }
        params.max_iterations = m.n;
    }
    if method == NormalMethod::ActiveSet && periodic {
        return Err(CaseError::field(
            "solver.method",
            "\"active_set\"",
            "the dense active set has no periodic form: use method = \"cg\" on a periodic grid",
        ));
    }
    if method == NormalMethod::ActiveSet && n[0] * n[1] > MAX_ACTIVE_SET_ELEMENTS {
        return Err(CaseError::field(
            "solver.method",
            "\"active_set\"",
            format!(
                "the dense active-set solver is for small grids (nx * ny <= {MAX_ACTIVE_SET_ELEMENTS}, \
                 here {}); use method = \"cg\"",
                n[0] * n[1]
            ),
        ));
    }
    Ok((method, params))
}
