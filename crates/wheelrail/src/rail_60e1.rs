//! The 60E1 (formerly UIC60) rail head (EN 13674-1), built from its published drawing
//! dimensions by tangency (references.md §W1.2).
//!
//! Coordinates: y \[m\] lateral from the head's centre line, z \[m\] upwards with z = 0 at the
//! top of the head. The head is symmetric. Published inputs: the crown arc R300 spans a chord
//! width of 20.456 mm, the R80 arcs reach a width of 52.053 mm, then R13 arcs turn into the
//! head flanks, inclined 1:20 to the vertical. Every arc is tangent to its neighbours; the
//! R13 arc ends where it is tangent to the flank. The head width that follows, 2 × 35.9998 mm
//! at 14.30 mm below the top, is the published 72 mm (tested, an independent check of the
//! construction). The flanks are modelled down to 30 mm below the top.

use crate::profile::{Profile, Segment};

const MM: f64 = 1e-3;

/// Published head width of 60E1 \[m\].
pub const HEAD_WIDTH: f64 = 0.072;

/// Depth below the top down to which the flanks are modelled \[m\].
pub const MODELLED_DEPTH: f64 = 0.030;

/// A symmetric rail head of three tangent arcs (radii `r`, the first centred on the centre
/// line) whose first two end at the half-widths `y1`, `y2`, followed by flanks of inclination
/// `flank` (horizontal per vertical) down to `depth` below the top. All lengths in metres.
pub fn three_arc_head(
    name: &str,
    r: [f64; 3],
    y1: f64,
    y2: f64,
    flank: f64,
    depth: f64,
) -> Profile {
    // Right half, z upwards. Crown arc centre (0, −r0).
    let c0 = (0.0, -r[0]);
    let p1 = (y1, c0.1 + (r[0] * r[0] - y1 * y1).sqrt());
    // Inner normal at p1 (towards c0); the next centre lies on it.
    let n1 = ((c0.0 - p1.0) / r[0], (c0.1 - p1.1) / r[0]);
    let c1 = (p1.0 + r[1] * n1.0, p1.1 + r[1] * n1.1);
    let p2 = (y2, c1.1 + (r[1] * r[1] - (y2 - c1.0).powi(2)).sqrt());
    let n2 = ((c1.0 - p2.0) / r[1], (c1.1 - p2.1) / r[1]);
    let c2 = (p2.0 + r[2] * n2.0, p2.1 + r[2] * n2.1);
    // Flank direction (flank, −1) (outwards as it goes down); outward normal (1, flank)/|.|.
    let norm = (1.0 + flank * flank).sqrt();
    let p3 = (c2.0 + r[2] / norm, c2.1 + r[2] * flank / norm);
    let slope = -1.0 / flank;
    let y4 = p3.0 + (p3.1 + depth) * flank;
    let right = [
        Segment::Arc {
            y0: 0.0,
            y1,
            yc: c0.0,
            zc: c0.1,
            r: r[0],
            upper: true,
        },
        Segment::Arc {
            y0: y1,
            y1: y2,
            yc: c1.0,
            zc: c1.1,
            r: r[1],
            upper: true,
        },
        Segment::Arc {
            y0: y2,
            y1: p3.0,
            yc: c2.0,
            zc: c2.1,
            r: r[2],
            upper: true,
        },
        Segment::Line {
            y0: p3.0,
            y1: y4,
            z0: p3.1,
            slope,
        },
    ];
    let half = Profile::new(name, right.to_vec()).expect("tangent arcs are joined");
    let mut segments: Vec<Segment> = half.mirrored().segments().to_vec();
    // The mirrored crown arc [−y1, 0] and the right one [0, y1] are one arc: merge them.
    let crown = segments.pop().expect("four segments");
    if let Segment::Arc {
        y0,
        yc,
        zc,
        r,
        upper,
        ..
    } = crown
    {
        segments.push(Segment::Arc {
            y0,
            y1,
            yc,
            zc,
            r,
            upper,
        });
    }
    segments.extend_from_slice(&right[1..]);
    Profile::new(name, segments).expect("the head's segments are ordered and joined")
}

/// The 60E1 head profile.
pub fn rail_60e1() -> Profile {
    three_arc_head(
        "60E1",
        [300.0 * MM, 80.0 * MM, 13.0 * MM],
        0.5 * 20.456 * MM,
        0.5 * 52.053 * MM,
        1.0 / 20.0,
        MODELLED_DEPTH,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tangent construction: value and slope continuous to rounding at all six breakpoints.
    #[test]
    fn value_and_slope_are_continuous_at_every_breakpoint() {
        let p = rail_60e1();
        let jumps = p.jumps();
        assert_eq!(jumps.len(), 6);
        for j in jumps {
            assert!(j.value.abs() < 1e-15, "value jump {} at {}", j.value, j.y);
            assert!(j.slope.abs() < 1e-11, "slope jump {} at {}", j.slope, j.y);
        }
    }

    /// The published head width, 72 mm, follows from the published radii and arc widths:
    /// the R13/flank tangent points are 72.00 mm apart (the drawing gives 72 to 0.1 mm;
    /// measured 71.9996 mm, the width the drawing's rounded inputs give).
    #[test]
    fn head_width_is_the_published_72_mm() {
        let p = rail_60e1();
        let flank_top = p.breakpoints()[5];
        let width = 2.0 * flank_top;
        assert!((width - HEAD_WIDTH).abs() < 0.01 * MM, "head width {width}");
        // Crown: z = 0 at the centre, curvature 1/300 mm.
        let (z, dz, d2z) = p.eval(0.0).unwrap();
        assert!(z.abs() < 1e-15 && dz.abs() < 1e-15);
        assert!((d2z + 1.0 / (300.0 * MM)).abs() < 1e-9);
        // Symmetric.
        for k in 0..=60 {
            let y = -36.5 * MM + 73.0 * MM * k as f64 / 60.0;
            assert!((p.z(y).unwrap() - p.z(-y).unwrap()).abs() < 1e-15);
        }
    }
}
