//! Vector operations on the active (contact) set and the cold-start pressure of NormCG.

use crate::grid::Grid;
use crate::material::Material;

/// Cold-start pressure for a prescribed force: the Hertzian shape p ∝ √(δ_H/2 − (h − h_min))
/// with δ_H the Hertz approach of the gap's local curvature at its minimum (exact in shape
/// for a quadratic gap: the overlap at δ/2 is the Hertz ellipse); a uniform pressure on the
/// lowest part of the gap when the gap has no curvature there (flat punch).
pub(super) fn initial_force_guess(
    grid: &Grid,
    material: &Material,
    gap: &[f64],
    force: f64,
    p: &mut [f64],
) {
    let (imin, hmin) =
        gap.iter()
            .copied()
            .enumerate()
            .fold(
                (0, f64::INFINITY),
                |(bi, bh), (i, h)| if h < bh { (i, h) } else { (bi, bh) },
            );
    if !hmin.is_finite() {
        return;
    }
    let (ix, iy) = (imin % grid.nx, imin / grid.nx);
    let curvature = |a: Option<f64>, b: Option<f64>, step: f64| -> Option<f64> {
        match (a, b) {
            (Some(a), Some(b)) if a.is_finite() && b.is_finite() => {
                let c = (a + b - 2.0 * hmin) / (2.0 * step * step);
                (c > 0.0).then_some(c)
            }
            (Some(a), None) | (None, Some(a)) if a.is_finite() => {
                let c = (a - hmin) / (step * step);
                (c > 0.0).then_some(c)
            }
            _ => None,
        }
    };
    let at = |jx: isize, jy: isize| -> Option<f64> {
        (jx >= 0 && jy >= 0 && (jx as usize) < grid.nx && (jy as usize) < grid.ny)
            .then(|| gap[jy as usize * grid.nx + jx as usize])
    };
    let (ix, iy) = (ix as isize, iy as isize);
    let ax = if grid.nx > 1 {
        curvature(at(ix - 1, iy), at(ix + 1, iy), grid.dx)
    } else {
        None
    };
    let by = if grid.ny > 1 {
        curvature(at(ix, iy - 1), at(ix, iy + 1), grid.dy)
    } else {
        None
    };
    let approach = match (ax, by) {
        (Some(a), Some(b)) => crate::hertz::Hertz::elliptic(a, b, material.e_star, force)
            .map(|h| h.approach)
            .ok(),
        (Some(a), None) if grid.ny == 1 => {
            // Line contact: a² = 4RF'/(πE*), overlap half-width at δ/2 equals a when δ = a²/R.
            let r = 0.5 / a;
            let a2 = 4.0 * r * force / grid.dy / (std::f64::consts::PI * material.e_star);
            Some(a2 / r)
        }
        _ => None,
    };
    match approach {
        Some(d) if d > 0.0 => {
            for (pi, &h) in p.iter_mut().zip(gap) {
                *pi = (0.5 * d - (h - hmin)).max(0.0).sqrt();
            }
        }
        _ => {
            let hmax = gap
                .iter()
                .copied()
                .filter(|h| h.is_finite())
                .fold(hmin, f64::max);
            let band = 1e-3 * (hmax - hmin);
            for (pi, &h) in p.iter_mut().zip(gap) {
                *pi = if h - hmin <= band { 1.0 } else { 0.0 };
            }
        }
    }
}

pub(super) fn masked_dot(a: &[f64], b: &[f64], active: &[bool]) -> f64 {
    a.iter()
        .zip(b)
        .zip(active)
        .filter(|(_, a)| **a)
        .map(|((x, y), _)| x * y)
        .sum()
}

pub(super) fn mask(x: &mut [f64], active: &[bool]) {
    for (v, &a) in x.iter_mut().zip(active) {
        if !a {
            *v = 0.0;
        }
    }
}

/// Subtract the mean over the elements of `list` from those elements.
pub(super) fn remove_list_mean(x: &mut [f64], list: &[usize]) {
    if list.is_empty() {
        return;
    }
    let s: f64 = list.iter().map(|&i| x[i]).sum();
    let mean = s / list.len() as f64;
    for &i in list {
        x[i] -= mean;
    }
}

/// Mean of h + u over the elements selected by `select(p)`: the approach that makes the
/// deformed distance mean-free there.
pub(super) fn mean_over(p: &[f64], gap: &[f64], u: &[f64], select: impl Fn(f64) -> bool) -> f64 {
    let (mut s, mut c) = (0.0, 0usize);
    for i in 0..p.len() {
        if select(p[i]) && gap[i].is_finite() {
            s += gap[i] + u[i];
            c += 1;
        }
    }
    if c == 0 { 0.0 } else { s / c as f64 }
}

/// [`mean_over`] for p > 0 with the loaded elements among those of `list` (p = 0 outside
/// the contact set).
pub(super) fn list_mean_loaded(list: &[usize], p: &[f64], gap: &[f64], u: &[f64]) -> f64 {
    let (mut s, mut c) = (0.0, 0usize);
    for &i in list {
        if p[i] > 0.0 && gap[i].is_finite() {
            s += gap[i] + u[i];
            c += 1;
        }
    }
    if c == 0 { 0.0 } else { s / c as f64 }
}

/// Mean of h + u over the elements of `list`.
pub(super) fn list_mean(list: &[usize], gap: &[f64], u: &[f64]) -> f64 {
    if list.is_empty() {
        return 0.0;
    }
    let s: f64 = list.iter().map(|&i| gap[i] + u[i]).sum();
    s / list.len() as f64
}

/// The grid rows holding the elements of `list` (ascending), as a range of row indices.
pub(super) fn contact_rows(list: &[usize], nx: usize) -> std::ops::Range<usize> {
    match (list.first(), list.last()) {
        (Some(&a), Some(&b)) => a / nx..b / nx + 1,
        _ => 0..0,
    }
}

/// Scale p (zero outside `list`) to the target sum; returns the factor (1 when p is zero).
pub(super) fn rescale(p: &mut [f64], list: &[usize], target_sum: f64) -> f64 {
    let s: f64 = list.iter().map(|&i| p[i]).sum();
    if s > 0.0 {
        let f = target_sum / s;
        list.iter().for_each(|&i| p[i] *= f);
        f
    } else {
        1.0
    }
}
