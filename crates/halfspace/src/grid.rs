//! The potential contact area: a uniform grid of rectangular elements.
//!
//! Element (ix, iy) covers [x0 + ix·dx, x0 + (ix+1)·dx] × [y0 + iy·dy, y0 + (iy+1)·dy] and
//! is stored at index `iy * nx + ix` (x fastest). Tractions are constant per element and
//! displacements are collocated at element centres (references.md §C3.2).

use crate::error::{ContactError, finite, in_range, positive};

/// Largest number of elements in one direction (2²⁰).
pub const MAX_ELEMENTS_PER_DIRECTION: usize = 1 << 20;

/// Largest number of elements nx·ny (2²² = 2048²).
pub const MAX_ELEMENTS: usize = 1 << 22;

/// Estimated memory per element \[bytes\] of the normal and tangential solvers on one grid:
/// influence tables and their spectra on the 2nx × 2ny zero-padded FFT grid (normal, three
/// tangential, steady and shifted variants, coupling) and the work vectors, about 160 doubles.
pub const WORKSPACE_BYTES_PER_ELEMENT: usize = 1280;

/// Allowed element sizes dx, dy \[m\]: 1 nm … 10 m (contact patches are µm to cm; the upper
/// bound leaves room for unit-scaled problems).
pub const ELEMENT_SIZE_RANGE: (f64, f64) = (1e-9, 10.0);

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
    /// `Ok` when an array named `name` has `found` = one value per element, else a
    /// [`ContactError::SizeMismatch`] naming it.
    pub(crate) fn check_len(&self, name: &'static str, found: usize) -> Result<(), ContactError> {
        if found != self.len() {
            return Err(ContactError::SizeMismatch {
                name,
                expected: self.len(),
                found,
            });
        }
        Ok(())
    }

    /// A validated grid: 1 ≤ nx, ny ≤ [`MAX_ELEMENTS_PER_DIRECTION`], nx·ny ≤ [`MAX_ELEMENTS`]
    /// (checked before anything is allocated; the error states the memory the solvers would
    /// need, [`Grid::workspace_bytes`]), element sizes in [`ELEMENT_SIZE_RANGE`], finite origin.
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
        check_size(nx, ny)?;
        let (lo, hi) = ELEMENT_SIZE_RANGE;
        positive("dx", dx)?;
        positive("dy", dy)?;
        in_range("dx", dx, lo, hi, "must lie in [1e-9, 10] m")?;
        in_range("dy", dy, lo, hi, "must lie in [1e-9, 10] m")?;
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

    /// Estimated memory \[bytes\] of the normal and tangential solvers on an nx × ny grid
    /// ([`WORKSPACE_BYTES_PER_ELEMENT`] per element; saturates instead of overflowing).
    pub fn workspace_bytes(nx: usize, ny: usize) -> u128 {
        nx as u128 * ny as u128 * WORKSPACE_BYTES_PER_ELEMENT as u128
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

/// The size limits of [`Grid::new`].
fn check_size(nx: usize, ny: usize) -> Result<(), ContactError> {
    let elements = nx as u128 * ny as u128;
    if nx > MAX_ELEMENTS_PER_DIRECTION
        || ny > MAX_ELEMENTS_PER_DIRECTION
        || elements > MAX_ELEMENTS as u128
    {
        return Err(ContactError::GridTooLarge {
            nx,
            ny,
            memory_gib: Grid::workspace_bytes(nx, ny) as f64 / (1u64 << 30) as f64,
        });
    }
    Ok(())
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

    #[test]
    fn oversized_grids_are_refused_before_allocating() {
        // Sizes that used to overflow the allocator or abort (issue 9).
        for (nx, ny) in [
            (44_000_000, 1),
            (usize::MAX >> 1, 64),
            (64, usize::MAX),
            (4096, 4096),
        ] {
            let err = Grid::new(nx, ny, 1e-4, 1e-4, 0.0, 0.0).unwrap_err();
            let text = err.to_string();
            assert!(matches!(err, ContactError::GridTooLarge { .. }), "{text}");
            assert!(
                text.contains(&nx.to_string()) && text.contains("GiB"),
                "{text}"
            );
        }
        // 4096² needs 4096² × 1280 bytes = 20 GiB: named in the message.
        let text = Grid::new(4096, 4096, 1e-4, 1e-4, 0.0, 0.0)
            .unwrap_err()
            .to_string();
        assert!(text.contains("20.0 GiB"), "{text}");
        // The limits themselves are accepted.
        assert!(Grid::new(2048, 2048, 1e-4, 1e-4, 0.0, 0.0).is_ok());
        assert!(Grid::new(MAX_ELEMENTS_PER_DIRECTION, 1, 1e-6, 1e-3, 0.0, 0.0).is_ok());
        assert!(Grid::new(MAX_ELEMENTS_PER_DIRECTION + 1, 1, 1e-6, 1e-3, 0.0, 0.0).is_err());
    }

    #[test]
    fn element_sizes_outside_the_physical_range_are_named() {
        for (dx, dy, name) in [
            (1e-300, 1e-4, "dx"),
            (1e300, 1e-4, "dx"),
            (1e-4, 1e-10, "dy"),
            (1e-4, 11.0, "dy"),
        ] {
            let err = Grid::new(8, 8, dx, dy, 0.0, 0.0).unwrap_err();
            assert!(
                matches!(err, ContactError::InvalidParameter { name: n, .. } if n == name),
                "{err}"
            );
            assert!(err.to_string().contains("[1e-9, 10] m"), "{err}");
        }
        assert!(Grid::new(8, 8, 1e-9, 10.0, 0.0, 0.0).is_ok());
    }
}
