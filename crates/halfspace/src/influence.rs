//! Influence coefficients of the elastic half-space for piecewise-constant pressure.
//!
//! Love's solution (Boussinesq load spread uniformly over a rectangle), in CONTACT's
//! combined-material form (contact.md §3.2): the normal displacement difference at an
//! observation point (x, y) due to a unit pressure on the element [ξ₁, ξ₂] × [η₁, η₂] is
//!
//! ```text
//! A_nn = (1 − ν)/(π G) · [[ X ln(Y + r) + Y ln(X + r) ]],   X = x − ξ, Y = y − η, r = √(X² + Y²)
//! ```
//!
//! with the corner double difference
//! `[[f]] = f(x−ξ₁, y−η₁) − f(x−ξ₂, y−η₁) − f(x−ξ₁, y−η₂) + f(x−ξ₂, y−η₂)`.
//! Far from the element A_nn → (1 − ν)/(π G) · ΔA / r (Boussinesq point load).

use crate::grid::Grid;
use crate::material::Material;

/// `X ln(Y + r)`, evaluated without cancellation when Y < 0 (then Y + r = X²/(r − Y)),
/// and with the limit 0 when X = 0.
fn x_log_y_plus_r(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let r = x.hypot(y);
    let log = if y >= 0.0 {
        (y + r).ln()
    } else {
        2.0 * x.abs().ln() - (r - y).ln()
    };
    x * log
}

/// The primitive F(X, Y) = X ln(Y + r) + Y ln(X + r) of the Love integrand.
fn love_primitive(x: f64, y: f64) -> f64 {
    x_log_y_plus_r(x, y) + x_log_y_plus_r(y, x)
}

/// The bracket [[X ln(Y+r) + Y ln(X+r)]] for an observation point at offset (`ox`, `oy`) [m]
/// from the centre of a `dx × dy` element. Has the dimension of a length.
pub fn love_bracket(ox: f64, oy: f64, dx: f64, dy: f64) -> f64 {
    let (x1, x2) = (ox + 0.5 * dx, ox - 0.5 * dx);
    let (y1, y2) = (oy + 0.5 * dy, oy - 0.5 * dy);
    love_primitive(x1, y1) - love_primitive(x2, y1) - love_primitive(x1, y2)
        + love_primitive(x2, y2)
}

/// Normal influence coefficient A_nn [m/Pa]: the normal displacement difference at offset
/// (`ox`, `oy`) from the centre of a `dx × dy` element loaded by a unit pressure.
pub fn normal_influence(material: &Material, ox: f64, oy: f64, dx: f64, dy: f64) -> f64 {
    (1.0 - material.nu) / (std::f64::consts::PI * material.g) * love_bracket(ox, oy, dx, dy)
}

/// The A_nn kernel tabulated at the offsets of the zero-padded periodic embedding:
/// a `2nx × 2ny` array (x fastest) whose entry (i, j) holds the influence at offset
/// (i', j')·(dx, dy), where i' = i for i < nx and i − 2nx otherwise (circulant order,
/// offsets −nx … nx−1, contact.md §3.3).
///
/// For a single-row grid (2D line contact, `ny = 1`) the row at offset −ny is zeroed as
/// CONTACT does; the matrix–vector product never uses it and the FFT preconditioner is
/// better conditioned without it.
pub fn circulant_kernel(material: &Material, grid: &Grid) -> Vec<f64> {
    let (mx, my) = (2 * grid.nx, 2 * grid.ny);
    // By symmetry the kernel depends on |offset| only: tabulate one quadrant.
    let mut quadrant = vec![0.0; (grid.nx + 1) * (grid.ny + 1)];
    for j in 0..=grid.ny {
        for i in 0..=grid.nx {
            quadrant[j * (grid.nx + 1) + i] = normal_influence(
                material,
                i as f64 * grid.dx,
                j as f64 * grid.dy,
                grid.dx,
                grid.dy,
            );
        }
    }
    let mut kernel = vec![0.0; mx * my];
    for j in 0..my {
        let oj = if j < grid.ny { j } else { my - j };
        for i in 0..mx {
            let oi = if i < grid.nx { i } else { mx - i };
            kernel[j * mx + i] = quadrant[oj * (grid.nx + 1) + oi];
        }
    }
    if grid.ny == 1 {
        for value in &mut kernel[mx..] {
            *value = 0.0;
        }
    }
    kernel
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn own_centre_of_square_element() {
        // contact.md §3.2: [[·]] = 4 s ln(1 + √2) = 3.525494 s at the element's own centre.
        let s = 1.0e-3;
        let bracket = love_bracket(0.0, 0.0, s, s);
        assert_relative_eq!(
            bracket,
            4.0 * s * (1.0 + 2f64.sqrt()).ln(),
            max_relative = 1e-14
        );
        assert_relative_eq!(bracket / s, 3.525494, max_relative = 2e-7);
    }

    #[test]
    fn contact_subsurf_case_1_approach() {
        // contact.md §3.2: 1 mm × 1 mm element, combined G = 1 N/mm², ν = 0.28, unit
        // pressure → 0.807984 mm approach (CONTACT's examples/subsurf.ref_out, case 1).
        // In SI: G = 1e6 Pa, p = 1e6 Pa, element 1e-3 m → 0.807984e-3 m.
        let m = Material::from_combined(1.0e6, 0.28).unwrap();
        let u = 1.0e6 * normal_influence(&m, 0.0, 0.0, 1.0e-3, 1.0e-3);
        assert_relative_eq!(u, 0.807984e-3, max_relative = 1e-6);
    }

    #[test]
    fn far_field_values() {
        // contact.md §3.2: bracket at r = 1, 2, 5, 20 element sizes (unit element):
        // 1.0380, 0.50509, 0.20033, 0.050005, tending to 1/r.
        for (r, expected) in [
            (1.0, 1.0380),
            (2.0, 0.50509),
            (5.0, 0.20033),
            (20.0, 0.050005),
        ] {
            let b = love_bracket(r, 0.0, 1.0, 1.0);
            assert_relative_eq!(b, expected, max_relative = 5e-5);
        }
        // Far away the Boussinesq point-load limit ΔA/r holds to O((s/r)²).
        let b = love_bracket(300.0, 400.0, 1.0, 2.0);
        assert_relative_eq!(b, 2.0 / 500.0, max_relative = 1e-5);
    }

    #[test]
    fn kernel_is_symmetric_in_offsets() {
        // Reciprocity: influence of offset (i, j) equals that of (−i, −j) and of mirrored ones.
        let m = Material::from_combined(1.0, 0.3).unwrap();
        let grid = Grid::new(5, 3, 0.7, 1.1, 0.0, 0.0).unwrap();
        let k = circulant_kernel(&m, &grid);
        let (mx, my) = (10, 6);
        for j in 1..my {
            for i in 1..mx {
                assert_eq!(k[j * mx + i], k[(my - j) * mx + (mx - i)]);
            }
        }
        assert_relative_eq!(
            k[0],
            normal_influence(&m, 0.0, 0.0, 0.7, 1.1),
            max_relative = 1e-15
        );
        assert_relative_eq!(
            k[mx + 2],
            normal_influence(&m, 1.4, 1.1, 0.7, 1.1),
            max_relative = 1e-15
        );
    }

    #[test]
    fn stable_near_element_edges() {
        // Observation points on the extension of an element edge (X = 0 or Y + r → 0):
        // the guarded logs give finite values that are continuous across the edge line.
        let on = love_bracket(0.5, 3.0, 1.0, 1.0);
        let near = love_bracket(0.5 + 1e-9, 3.0, 1.0, 1.0);
        assert!(on.is_finite());
        assert_relative_eq!(on, near, max_relative = 1e-8);
    }
}
