//! Influence coefficients of the elastic half-space for piecewise-constant pressure.
//!
//! Love's solution (Boussinesq load spread uniformly over a rectangle), in CONTACT's
//! combined-material form (references.md §C3.2): the normal displacement difference at an
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

/// The bracket [[X ln(Y+r) + Y ln(X+r)]] for an observation point at offset (`ox`, `oy`) \[m\]
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
/// offsets −nx … nx−1, references.md §C3.3).
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

/// `X·atan(Y/X)` with the limit 0 at X = 0 (|atan| ≤ π/2).
fn x_atan_y_over_x(x: f64, y: f64) -> f64 {
    if x == 0.0 { 0.0 } else { x * (y / x).atan() }
}

/// `Y·ln r` with the limit 0 at Y = 0 (also when r → 0).
fn y_log_r(x: f64, y: f64) -> f64 {
    if y == 0.0 { 0.0 } else { y * x.hypot(y).ln() }
}

/// Corner double difference [[f]] of a primitive `f(X, Y)` for an observation point at offset
/// (`ox`, `oy`) [m] from the centre of a `dx × dy` element (references.md §C3.2).
fn bracket(f: impl Fn(f64, f64) -> f64, ox: f64, oy: f64, dx: f64, dy: f64) -> f64 {
    let (x1, x2) = (ox + 0.5 * dx, ox - 0.5 * dx);
    let (y1, y2) = (oy + 0.5 * dy, oy - 0.5 * dy);
    f(x1, y1) - f(x2, y1) - f(x1, y2) + f(x2, y2)
}

/// The tangential and coupling influence coefficients at one offset [m/Pa]
/// (references.md §C3.2, CONTACT's combined-material form, everything over π G):
///
/// ```text
/// A_xx = 1/(πG) [[ Y ln(X+r) + (1−ν) X ln(Y+r) ]]
/// A_yy = 1/(πG) [[ X ln(Y+r) + (1−ν) Y ln(X+r) ]]
/// A_xy = A_yx = −ν/(πG) [[ r ]]
/// A_xn = −K/(πG) [[ Y ln r + X atan(Y/X) ]]        (u_x from p_n; A_nx = −A_xn)
/// A_yn = −K/(πG) [[ X ln r + Y atan(X/Y) ]]        (u_y from p_n; A_ny = −A_yn)
/// ```
///
/// Their integrands (the mixed second derivatives of the primitives) are Cerruti's and
/// Boussinesq's point-load solutions: A_xx ~ ΔA/(πG)·((1−ν)/r + ν X²/r³),
/// A_xy ~ ΔA/(πG)·ν X Y/r³, A_xn ~ −ΔA K/(πG)·X/r².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentialInfluence {
    pub xx: f64,
    pub xy: f64,
    pub yy: f64,
    pub xn: f64,
    pub yn: f64,
}

/// Tangential and coupling influence coefficients of a `dx × dy` element loaded by a unit
/// traction, observed at offset (`ox`, `oy`) from its centre. See [`TangentialInfluence`].
pub fn tangential_influence(
    material: &Material,
    ox: f64,
    oy: f64,
    dx: f64,
    dy: f64,
) -> TangentialInfluence {
    let nu = material.nu;
    let scale = 1.0 / (std::f64::consts::PI * material.g);
    let xx = bracket(
        |x, y| x_log_y_plus_r(y, x) + (1.0 - nu) * x_log_y_plus_r(x, y),
        ox,
        oy,
        dx,
        dy,
    );
    let yy = bracket(
        |x, y| x_log_y_plus_r(x, y) + (1.0 - nu) * x_log_y_plus_r(y, x),
        ox,
        oy,
        dx,
        dy,
    );
    let rr = bracket(|x, y| x.hypot(y), ox, oy, dx, dy);
    let (xn, yn) = if material.k == 0.0 {
        (0.0, 0.0)
    } else {
        (
            bracket(|x, y| y_log_r(x, y) + x_atan_y_over_x(x, y), ox, oy, dx, dy),
            bracket(|x, y| y_log_r(y, x) + x_atan_y_over_x(y, x), ox, oy, dx, dy),
        )
    };
    TangentialInfluence {
        xx: scale * xx,
        xy: -nu * scale * rr,
        yy: scale * yy,
        xn: -material.k * scale * xn,
        yn: -material.k * scale * yn,
    }
}

/// Which coefficient of [`TangentialInfluence`] a kernel table holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Component {
    Xx,
    Xy,
    Yy,
    Xn,
    Yn,
}

impl TangentialInfluence {
    /// The coefficient of one component.
    pub fn get(&self, c: Component) -> f64 {
        match c {
            Component::Xx => self.xx,
            Component::Xy => self.xy,
            Component::Yy => self.yy,
            Component::Xn => self.xn,
            Component::Yn => self.yn,
        }
    }
}

/// Tangential kernels at all element offsets of `grid`, in the "centred" layout: a
/// `(2nx − 1) × (2ny − 1)` array (x fastest) whose entry (i, j) is the coefficient at offset
/// ((i − nx + 1)·dx + `shift`, (j − ny + 1)·dy). `shift` \[m\] moves the observation points
/// along x: with `shift = δq` it gives CONTACT's kernel "C_v" of the displacement that the
/// particles now at x had one rolling step δq earlier (references.md §C3.5).
/// Returns the tables of `components` in order.
pub fn tangential_offset_tables(
    material: &Material,
    grid: &Grid,
    shift: f64,
    components: &[Component],
) -> Vec<Vec<f64>> {
    let (wx, wy) = (2 * grid.nx - 1, 2 * grid.ny - 1);
    let mut tables = vec![vec![0.0; wx * wy]; components.len()];
    for j in 0..wy {
        let oy = (j as f64 - (grid.ny as f64 - 1.0)) * grid.dy;
        for i in 0..wx {
            let ox = (i as f64 - (grid.nx as f64 - 1.0)) * grid.dx + shift;
            let t = tangential_influence(material, ox, oy, grid.dx, grid.dy);
            for (table, &c) in tables.iter_mut().zip(components) {
                table[j * wx + i] = t.get(c);
            }
        }
    }
    tables
}

/// Re-order a centred offset table (see [`tangential_offset_tables`]) into the circulant
/// `2nx × 2ny` layout of [`crate::convolution::FftConvolution::kernel_spectrum`]; the unused
/// offsets −nx and −ny are set to zero (they never reach an output element).
pub fn circulant_from_centred(grid: &Grid, centred: &[f64]) -> Vec<f64> {
    let (nx, ny) = (grid.nx, grid.ny);
    let (wx, mx, my) = (2 * nx - 1, 2 * nx, 2 * ny);
    let mut out = vec![0.0; mx * my];
    for j in 0..my {
        let oj = if j < ny {
            j as isize
        } else {
            j as isize - my as isize
        };
        if oj <= -(ny as isize) {
            continue;
        }
        let cj = (oj + ny as isize - 1) as usize;
        for i in 0..mx {
            let oi = if i < nx {
                i as isize
            } else {
                i as isize - mx as isize
            };
            if oi <= -(nx as isize) {
                continue;
            }
            let ci = (oi + nx as isize - 1) as usize;
            out[j * mx + i] = centred[cj * wx + ci];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn own_centre_of_square_element() {
        // references.md §C3.2: [[·]] = 4 s ln(1 + √2) = 3.525494 s at the element's own centre.
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
        // references.md §C3.2: 1 mm × 1 mm element, combined G = 1 N/mm², ν = 0.28, unit
        // pressure → 0.807984 mm approach (CONTACT's examples/subsurf.ref_out, case 1).
        // In SI: G = 1e6 Pa, p = 1e6 Pa, element 1e-3 m → 0.807984e-3 m.
        let m = Material::from_combined(1.0e6, 0.28).unwrap();
        let u = 1.0e6 * normal_influence(&m, 0.0, 0.0, 1.0e-3, 1.0e-3);
        assert_relative_eq!(u, 0.807984e-3, max_relative = 1e-6);
    }

    #[test]
    fn far_field_values() {
        // references.md §C3.2: bracket at r = 1, 2, 5, 20 element sizes (unit element):
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
