//! The potential contact area: a uniform grid of rectangular elements.
//!
//! Element (ix, iy) covers [x0 + ix·dx, x0 + (ix+1)·dx] × [y0 + iy·dy, y0 + (iy+1)·dy] and
//! is stored at index `iy * nx + ix` (x fastest). Tractions are constant per element and
//! displacements are collocated at element centres (references.md §C3.2).

use crate::error::{ContactError, finite, positive};

/// A uniform rectangular grid of `nx × ny` elements of size `dx × dy` \[m\],
/// with lower-left corner (`x0`, `y0`) \[m\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub x0: f64,
    pub y0: f64,
}

impl Grid {
    /// A validated grid: at least one element in each direction, positive finite sizes.
    pub fn new(
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        x0: f64,
        y0: f64,
    ) -> Result<Self, ContactError> {
        if nx == 0 {
            return Err(ContactError::InvalidParameter {
                name: "nx",
                value: 0.0,
                reason: "the grid needs at least one element in x",
            });
        }
        if ny == 0 {
            return Err(ContactError::InvalidParameter {
                name: "ny",
                value: 0.0,
                reason: "the grid needs at least one element in y",
            });
        }
        positive("dx", dx)?;
        positive("dy", dy)?;
        finite("x0", x0)?;
        finite("y0", y0)?;
        Ok(Grid {
            nx,
            ny,
            dx,
            dy,
            x0,
            y0,
        })
    }

    /// A grid of `nx × ny` elements centred on (`xc`, `yc`).
    pub fn centred(
        nx: usize,
        ny: usize,
        dx: f64,
        dy: f64,
        xc: f64,
        yc: f64,
    ) -> Result<Self, ContactError> {
        Self::new(
            nx,
            ny,
            dx,
            dy,
            xc - 0.5 * nx as f64 * dx,
            yc - 0.5 * ny as f64 * dy,
        )
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false for a validated grid.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Element area ΔA = dx·dy \[m²\].
    pub fn element_area(&self) -> f64 {
        self.dx * self.dy
    }

    /// x of the centre of column `ix`.
    pub fn x(&self, ix: usize) -> f64 {
        self.x0 + (ix as f64 + 0.5) * self.dx
    }

    /// y of the centre of row `iy`.
    pub fn y(&self, iy: usize) -> f64 {
        self.y0 + (iy as f64 + 0.5) * self.dy
    }

    /// Centre (x, y) of element `index`.
    pub fn centre(&self, index: usize) -> (f64, f64) {
        (self.x(index % self.nx), self.y(index / self.nx))
    }

    /// Sample a function of (x, y) at every element centre.
    pub fn sample(&self, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.len());
        for iy in 0..self.ny {
            let y = self.y(iy);
            for ix in 0..self.nx {
                out.push(f(self.x(ix), y));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centres_and_indexing() {
        let g = Grid::new(4, 3, 0.5, 2.0, -1.0, 0.0).unwrap();
        assert_eq!(g.len(), 12);
        assert_eq!(g.centre(0), (-0.75, 1.0));
        assert_eq!(g.centre(5), (-0.25, 3.0));
        let c = Grid::centred(2, 2, 1.0, 1.0, 3.0, 4.0).unwrap();
        assert_eq!(c.x0, 2.0);
        assert_eq!(c.y0, 3.0);
    }

    #[test]
    fn zero_grid_is_rejected() {
        assert!(matches!(
            Grid::new(0, 3, 1.0, 1.0, 0.0, 0.0),
            Err(ContactError::InvalidParameter { name: "nx", .. })
        ));
        assert!(matches!(
            Grid::new(3, 3, 0.0, 1.0, 0.0, 0.0),
            Err(ContactError::InvalidParameter { name: "dx", .. })
        ));
        assert!(matches!(
            Grid::new(3, 3, 1.0, f64::NAN, 0.0, 0.0),
            Err(ContactError::InvalidParameter { name: "dy", .. })
        ));
    }
}
