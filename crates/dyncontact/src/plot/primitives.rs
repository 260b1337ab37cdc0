//! Drawing primitives of the line charts: the colours, axis ranges, line segments (broken at
//! non-finite points, thinned, clipped to the axes), tick labels and the legend layout.

use plotters::style::RGBColor;

/// Line colours in order (Tableau 10 reordered, then black and navy): twelve distinct colours,
/// so a panel of up to twelve series never repeats one (the sweep plots draw ten trains, the
/// envelope and the limit).
pub(crate) const COLOURS: [RGBColor; 12] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(0, 0, 0),
    RGBColor(0, 0, 128),
];

/// Largest magnitude a plotted value may have (beyond it the axis labels and the line
/// rasterisation lose meaning; such panels are skipped with a note).
pub(crate) const PLOT_MAX_MAGNITUDE: f64 = 1e100;
/// Points drawn per series at most: longer series are thinned by keeping each bucket's
/// minimum and maximum (peaks survive), which bounds the plotting time.
pub(crate) const PLOT_MAX_POINTS: usize = 8000;

/// The axis range of `values` with a 4 % margin (non-finite values ignored), or why the panel
/// cannot be plotted.
pub(crate) fn range_of(values: impl Iterator<Item = f64>) -> Result<(f64, f64), String> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return Ok((0.0, 1.0));
    }
    let big = lo.abs().max(hi.abs());
    if big > PLOT_MAX_MAGNITUDE || (big > 0.0 && big < 1.0 / PLOT_MAX_MAGNITUDE) {
        return Err(format!(
            "values up to {big:.3e} in magnitude are outside the plottable range [1e-100, 1e100]"
        ));
    }
    if hi - lo <= 1e-12 * big {
        let pad = if big == 0.0 { 1.0 } else { 0.05 * big };
        return Ok((lo - pad, hi + pad));
    }
    let pad = 0.04 * (hi - lo);
    Ok((lo - pad, hi + pad))
}

/// The finite runs of a series (a NaN or infinity breaks the line), each thinned to at most
/// [`PLOT_MAX_POINTS`] points by per-bucket minimum and maximum.
pub(crate) fn drawable_segments(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut segments = Vec::new();
    for run in points.split(|(x, y)| !(x.is_finite() && y.is_finite())) {
        if run.is_empty() {
            continue;
        }
        if run.len() <= PLOT_MAX_POINTS {
            segments.push(run.to_vec());
            continue;
        }
        let buckets = PLOT_MAX_POINTS / 2;
        let size = run.len().div_ceil(buckets);
        let mut thin = Vec::with_capacity(2 * buckets + 1);
        for chunk in run.chunks(size) {
            let (mut i_lo, mut i_hi) = (0, 0);
            for (i, p) in chunk.iter().enumerate() {
                if p.1 < chunk[i_lo].1 {
                    i_lo = i;
                }
                if p.1 > chunk[i_hi].1 {
                    i_hi = i;
                }
            }
            thin.push(chunk[i_lo.min(i_hi)]);
            if i_lo != i_hi {
                thin.push(chunk[i_lo.max(i_hi)]);
            }
        }
        thin.push(run[run.len() - 1]);
        segments.push(thin);
    }
    segments
}

/// A straight piece of a line, from one point to another.
pub(crate) type Segment = ((f64, f64), (f64, f64));

/// The part of the segment a–b inside the box \[x0, x1\] × \[y0, y1\] (Liang–Barsky), if any.
pub(crate) fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<Segment> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some((
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ))
}

/// Tick labels without redundant digits: the precision follows the axis span (ticks are at
/// most span/20 apart in plotters' choice), trailing zeros are dropped and −0 reads 0.
pub(crate) fn tick_formatter(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let span = (hi - lo).abs();
    let big = lo.abs().max(hi.abs());
    let scientific = big >= 1e6 || (big > 0.0 && big < 1e-3);
    let decimals = if span > 0.0 {
        (-(span / 100.0).log10()).ceil().clamp(0.0, 12.0) as usize
    } else {
        3
    };
    move |v: &f64| {
        // A tick at zero computed as a round-off residue (5.4e-20 on a ±4e-4 axis) reads 0.
        if v.abs() <= 1e-9 * span {
            return "0".to_string();
        }
        let text = if scientific {
            let s = format!("{v:.3e}");
            match s.split_once('e') {
                Some((m, e)) => {
                    let m = if m.contains('.') {
                        m.trim_end_matches('0').trim_end_matches('.')
                    } else {
                        m
                    };
                    format!("{m}e{e}")
                }
                None => s,
            }
        } else {
            let s = format!("{v:.decimals$}");
            if s.contains('.') {
                s.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                s
            }
        };
        if text == "-0" || text.starts_with("-0e") {
            text[1..].to_string()
        } else {
            text
        }
    }
}

pub(crate) const LEGEND_ROW: u32 = 20;

/// Lays legend entries out in rows of at most `width` pixels: (entry, x offset, row).
pub(crate) fn legend_layout(labels: &[(usize, u32)], width: u32) -> Vec<(usize, u32, u32)> {
    let (mut x, mut row) = (0u32, 0u32);
    let mut out = Vec::new();
    for &(k, text_w) in labels {
        let w = 34 + text_w + 18;
        if x > 0 && x + w > width {
            x = 0;
            row += 1;
        }
        out.push((k, x, row));
        x += w;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_sane_or_refused() {
        assert_eq!(range_of([0.0, 0.0].into_iter()), Ok((-1.0, 1.0)));
        assert_eq!(range_of([f64::NAN].into_iter()), Ok((0.0, 1.0)));
        let (lo, hi) = range_of([1.0, 2.0, f64::INFINITY].into_iter()).unwrap();
        assert!((lo - 0.96).abs() < 1e-12 && (hi - 2.04).abs() < 1e-12);
        assert!(range_of([1e-299, 2e-299].into_iter()).is_err());
        assert!(range_of([0.0, 3e290].into_iter()).is_err());
    }

    #[test]
    fn segments_break_at_non_finite_points_and_keep_peaks() {
        let s = drawable_segments(&[(0.0, 1.0), (1.0, f64::NAN), (2.0, 3.0), (3.0, 4.0)]);
        assert_eq!(s, vec![vec![(0.0, 1.0)], vec![(2.0, 3.0), (3.0, 4.0)]]);
        let long: Vec<(f64, f64)> = (0..100_000)
            .map(|i| (i as f64, if i == 54_321 { 9.0 } else { 0.0 }))
            .collect();
        let thin = drawable_segments(&long);
        assert!(thin[0].len() <= PLOT_MAX_POINTS + 1);
        assert!(thin[0].contains(&(54_321.0, 9.0)));
        assert!(thin[0].windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn segments_are_clipped_to_the_box() {
        let b = ((0.0, 1.0), (0.0, 1.0));
        // Inside: unchanged.
        assert_eq!(
            clip_segment((0.2, 0.2), (0.8, 0.5), b.0, b.1),
            Some(((0.2, 0.2), (0.8, 0.5)))
        );
        // Through the box from below-left to above-right: cut at the frame.
        let (a, c) = clip_segment((-1.0, -1.0), (2.0, 2.0), b.0, b.1).unwrap();
        assert!((a.0 - 0.0).abs() < 1e-15 && (a.1 - 0.0).abs() < 1e-15);
        assert!((c.0 - 1.0).abs() < 1e-15 && (c.1 - 1.0).abs() < 1e-15);
        // A spike leaving through the top: ends on y = 1 at x = 0.5 + 0.5/10.
        let (_, c) = clip_segment((0.5, 0.0), (0.6, 10.0), b.0, b.1).unwrap();
        assert!((c.1 - 1.0).abs() < 1e-15 && (c.0 - 0.51).abs() < 1e-15);
        // Outside entirely.
        assert_eq!(clip_segment((2.0, 0.0), (3.0, 1.0), b.0, b.1), None);
        assert_eq!(clip_segment((-1.0, 2.0), (2.0, 2.0), b.0, b.1), None);
    }

    #[test]
    fn tick_labels_have_no_redundant_digits() {
        let f = tick_formatter(0.0, 10.0);
        assert_eq!(f(&2.0), "2");
        assert_eq!(f(&2.5), "2.5");
        let f = tick_formatter(-1.0, 1.0);
        assert_eq!(f(&-0.0), "0");
        assert_eq!(f(&-1e-17), "0");
        assert_eq!(f(&0.4), "0.4");
        assert_eq!(f(&-0.25), "-0.25");
        // Round-off residue of a zero tick on a small-valued axis.
        let f = tick_formatter(-4.16e-4, 1.6e-5);
        assert_eq!(f(&5.421e-20), "0");
        assert_eq!(f(&-1e-4), "-1e-4");
        let f = tick_formatter(0.0, 3e9);
        assert_eq!(f(&2e9), "2e9");
        assert_eq!(f(&2.5e9), "2.5e9");
    }
}
