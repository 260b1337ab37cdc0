//! Undeformed gaps h(x, y) between the two bodies, and the automatic potential contact area.
//!
//! Coordinates are relative to the point of first contact (the gap's minimum, h = 0 there).
//! Any other gap can be sampled from a closure with [`crate::Grid::sample`].

use crate::error::{ContactError, positive};
use crate::grid::Grid;
use crate::hertz::{Hertz, LineHertz};
use crate::material::Material;
use crate::normcg::NormalLoad;

/// A gap shape.
#[derive(Debug, Clone, PartialEq)]
pub enum GapShape {
    /// h = A x² + B y², A and B in 1/m (Hertz's quadratic approximation).
    Quadratic { a: f64, b: f64 },
    /// A sphere of radius R on a plane, exact: h = R − √(R² − r²) (excluded for r ≥ R).
    Sphere { radius: f64 },
    /// A cylinder of radius R with its axis along y and length L on a plane:
    /// h = R − √(R² − x²) for |y| ≤ L/2, excluded beyond its ends.
    Cylinder { radius: f64, length: f64 },
    /// A flat circular punch of radius a with rounded edges of radius R_e:
    /// h = 0 for r ≤ a, h = (r − a)²/(2R_e) beyond (non-Hertzian).
    Punch { radius: f64, edge_radius: f64 },
    /// Values per element of a given grid, x fastest.
    Table { values: Vec<f64> },
}

impl GapShape {
    /// Validate the parameters of the shape.
    pub fn validate(&self) -> Result<(), ContactError> {
        match self {
            GapShape::Quadratic { a, b } => {
                positive("A", *a)?;
                positive("B", *b)?;
            }
            GapShape::Sphere { radius } => {
                positive("radius", *radius)?;
            }
            GapShape::Cylinder { radius, length } => {
                positive("radius", *radius)?;
                positive("length", *length)?;
            }
            GapShape::Punch {
                radius,
                edge_radius,
            } => {
                positive("radius", *radius)?;
                positive("edge_radius", *edge_radius)?;
            }
            GapShape::Table { values } => {
                if values.iter().any(|v| !v.is_finite()) {
                    return Err(ContactError::InvalidParameter {
                        name: "table",
                        value: f64::NAN,
                        reason: "every tabulated gap value must be finite",
                    });
                }
            }
        }
        Ok(())
    }

    /// The gap at every element centre of `grid`. Excluded elements get `f64::INFINITY`.
    pub fn sample(&self, grid: &Grid) -> Result<Vec<f64>, ContactError> {
        self.validate()?;
        Ok(match self {
            GapShape::Quadratic { a, b } => grid.sample(|x, y| a * x * x + b * y * y),
            GapShape::Sphere { radius } => grid.sample(|x, y| {
                let r2 = x * x + y * y;
                if r2 < radius * radius {
                    // R − √(R² − r²) = r²/(R + √(R² − r²)), free of cancellation.
                    r2 / (radius + (radius * radius - r2).sqrt())
                } else {
                    f64::INFINITY
                }
            }),
            GapShape::Cylinder { radius, length } => grid.sample(|x, y| {
                if y.abs() <= 0.5 * length * (1.0 + 1e-12) && x.abs() < *radius {
                    x * x / (radius + (radius * radius - x * x).sqrt())
                } else {
                    f64::INFINITY
                }
            }),
            GapShape::Punch {
                radius,
                edge_radius,
            } => grid.sample(|x, y| {
                let r = x.hypot(y);
                if r <= *radius {
                    0.0
                } else {
                    (r - radius).powi(2) / (2.0 * edge_radius)
                }
            }),
            GapShape::Table { values } => {
                if values.len() != grid.len() {
                    return Err(ContactError::SizeMismatch {
                        name: "table",
                        expected: grid.len(),
                        found: values.len(),
                    });
                }
                values.clone()
            }
        })
    }

    /// The curvatures (A, B) of the gap's quadratic approximation at its minimum, where the
    /// shape has one (a cylinder has B = 0).
    pub fn curvatures(&self) -> Option<(f64, f64)> {
        match *self {
            GapShape::Quadratic { a, b } => Some((a, b)),
            GapShape::Sphere { radius } => Some((0.5 / radius, 0.5 / radius)),
            GapShape::Cylinder { radius, .. } => Some((0.5 / radius, 0.0)),
            GapShape::Punch { .. } | GapShape::Table { .. } => None,
        }
    }

    /// The Hertz solution of this gap's quadratic approximation under `load`, if the gap
    /// is a point contact (quadratic or sphere).
    pub fn hertz(&self, material: &Material, load: NormalLoad) -> Option<Hertz> {
        let (a, b) = match self {
            GapShape::Quadratic { .. } | GapShape::Sphere { .. } => self.curvatures()?,
            _ => return None,
        };
        match load {
            NormalLoad::Force(f) => Hertz::elliptic(a, b, material.e_star, f).ok(),
            NormalLoad::Approach(d) => Hertz::elliptic_at_approach(a, b, material.e_star, d).ok(),
        }
    }
}

/// Default number of elements per direction of an automatic grid.
pub const AUTO_GRID_ELEMENTS: usize = 64;

/// Ratio of the automatic grid's half-width to the estimated contact semi-axis: the patch
/// covers 1/1.25 = 0.8 of the grid, leaving a margin of exterior elements on every side.
pub const AUTO_GRID_MARGIN: f64 = 1.25;

/// An automatic potential contact area for `shape` under `load`: centred on the gap's
/// minimum, `n × n` elements (one row of length L for a cylinder: 2D line contact) whose
/// extent is `AUTO_GRID_MARGIN` times the Hertz estimate of the patch.
pub fn auto_grid(
    shape: &GapShape,
    material: &Material,
    load: NormalLoad,
    n: usize,
) -> Result<Grid, ContactError> {
    shape.validate()?;
    if n == 0 {
        return Err(ContactError::InvalidParameter {
            name: "n",
            value: 0.0,
            reason: "the automatic grid needs at least one element",
        });
    }
    match (shape, load) {
        (
            GapShape::Punch {
                radius,
                edge_radius,
            },
            load,
        ) => {
            // The patch is the flat face plus the part of the rounding pressed in; bound it by
            // the overlap at the approach of a rigid flat punch (F = 2aE*δ) plus a margin.
            let d = match load {
                NormalLoad::Force(f) => positive("force", f)? / (2.0 * radius * material.e_star),
                NormalLoad::Approach(d) => positive("approach", d)?,
            };
            let half = AUTO_GRID_MARGIN * (radius + (2.0 * edge_radius * d).sqrt());
            Grid::centred(n, n, 2.0 * half / n as f64, 2.0 * half / n as f64, 0.0, 0.0)
        }
        (GapShape::Table { .. }, _) => Err(ContactError::InvalidParameter {
            name: "grid",
            value: f64::NAN,
            reason: "a tabulated gap needs an explicit grid",
        }),
        (GapShape::Cylinder { radius, length }, load) => {
            let a = match load {
                NormalLoad::Force(f) => {
                    LineHertz::new(*radius, material.e_star, positive("force", f)? / length)?.a
                }
                // Overlap half-width √(2Rδ) bounds the contact half-width √(Rδ)… from above.
                NormalLoad::Approach(d) => {
                    (2.0 * radius * positive("approach", d)?).sqrt() / 2f64.sqrt()
                }
            };
            let dx = 2.0 * AUTO_GRID_MARGIN * a / n as f64;
            Grid::centred(n, 1, dx, *length, 0.0, 0.0)
        }
        (shape, load) => {
            let hertz = shape
                .hertz(material, load)
                .ok_or(ContactError::InvalidParameter {
                    name: "load",
                    value: f64::NAN,
                    reason: "the load must be positive to estimate the contact patch",
                })?;
            let dx = 2.0 * AUTO_GRID_MARGIN * hertz.a / n as f64;
            let dy = 2.0 * AUTO_GRID_MARGIN * hertz.b / n as f64;
            Grid::centred(n, n, dx, dy, 0.0, 0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sphere_gap_is_exact_and_close_to_parabola() {
        let g = Grid::centred(4, 4, 1e-4, 1e-4, 0.0, 0.0).unwrap();
        let h = GapShape::Sphere { radius: 0.01 }.sample(&g).unwrap();
        let (x, y) = g.centre(0);
        let r2 = x * x + y * y;
        assert_relative_eq!(h[0], 0.01 - (1e-4 - r2).sqrt(), max_relative = 1e-9);
        let q = GapShape::Quadratic { a: 50.0, b: 50.0 }.sample(&g).unwrap();
        // The exact sphere differs from its parabola by the factor 1 + r²/(4R²) + …: 1.1e-4 here.
        assert_relative_eq!(h[0], q[0], max_relative = 2e-4);
    }

    #[test]
    fn cylinder_excludes_beyond_its_ends() {
        let g = Grid::centred(2, 4, 1e-4, 1.0, 0.0, 0.0).unwrap();
        let h = GapShape::Cylinder {
            radius: 0.1,
            length: 2.0,
        }
        .sample(&g)
        .unwrap();
        assert!(h[0].is_infinite());
        assert!(h[2].is_finite() && h[5].is_finite());
        assert!(h[7].is_infinite());
    }

    #[test]
    fn auto_grid_covers_the_hertz_patch_with_margin() {
        let m = Material::identical(210e9, 0.3).unwrap();
        let shape = GapShape::Quadratic { a: 50.0, b: 100.0 };
        let grid = auto_grid(&shape, &m, NormalLoad::Force(1000.0), 64).unwrap();
        let h = shape.hertz(&m, NormalLoad::Force(1000.0)).unwrap();
        assert_relative_eq!(grid.nx as f64 * grid.dx, 2.5 * h.a, max_relative = 1e-12);
        assert_relative_eq!(grid.ny as f64 * grid.dy, 2.5 * h.b, max_relative = 1e-12);
        assert!(
            auto_grid(
                &GapShape::Table { values: vec![0.0] },
                &m,
                NormalLoad::Force(1.0),
                8
            )
            .is_err()
        );
    }
}
