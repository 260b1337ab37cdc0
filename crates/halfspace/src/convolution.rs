//! Discrete convolution with a block-Toeplitz influence kernel by zero-padded FFT.
//!
//! For an `nx × ny` grid the influence matrix depends only on element offsets, so
//! `u = A p` is a 2D linear convolution. Embedding it in a periodic `2nx × 2ny` problem and
//! zero-padding p makes the circular FFT convolution exact (the DC-FFT idea, Liu, Wang & Liu
//! 2000; CONTACT does the same, references.md §C3.3):
//!
//! 1. real-to-complex FFT of each of the `ny` non-zero padded rows (length 2nx); an input
//!    row that is zero (outside NormCG's contact set) is skipped, its spectrum is zero;
//! 2. complex FFT of each of the `nx + 1` spectral columns (length 2ny);
//! 3. multiplication by the cached kernel spectrum (scaled by 1/(4 nx ny));
//! 4. the inverse transforms, computing only the `ny` output rows that are kept, or a band
//!    of them ([`FftConvolution::apply_rows`]: NormCG's preconditioner, needed on the rows
//!    of the contact set only).
//!
//! Both skips leave every computed value unchanged bit for bit (each row transform is
//! independent of the others).
//! [`FftConvolution`] owns the plans and every buffer; [`FftConvolution::apply`] does not
//! allocate. Rows and columns are transformed in parallel with rayon on large grids, each
//! task with its own preallocated scratch.
//!
//! Tested through the influence operators ([`crate::operator`]) against their direct O(n²)
//! sums: the symmetric normal kernel and the non-symmetric shifted and coupling kernels of
//! the tangential problem (the complex spectrum path), on grids from 1 × 1 up
//! (tests/influence_operator.rs, tests/normal_contact.rs).

use std::sync::Arc;

use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

/// Grids with at least this many elements use both cores (below, thread hand-off costs more
/// than it saves).
const PARALLEL_THRESHOLD: usize = 128 * 128;

/// Tile edge of the cache-blocked transposes between row and column layouts.
const TILE: usize = 32;

/// Spectrum of a convolution kernel in the operator's layout: `(nx + 1)` columns of `2ny`
/// complex values, already scaled by the inverse-FFT normalisation 1/(4 nx ny).
#[derive(Debug, Clone)]
pub struct KernelSpectrum {
    values: Vec<Complex64>,
}

impl KernelSpectrum {
    /// The spectrum of the inverse kernel (element-wise reciprocal): applied as a
    /// convolution it approximates A⁻¹ (Vollebregt's FFT preconditioner, references.md §C3.4).
    /// `None` if a Fourier coefficient vanishes.
    pub fn reciprocal(&self, scale: f64) -> Option<KernelSpectrum> {
        let mut values = Vec::with_capacity(self.values.len());
        for &v in &self.values {
            if v.norm() == 0.0 || !v.re.is_finite() {
                return None;
            }
            // (v·s)⁻¹·s = 1/(v s²)·s² … the stored values carry one factor `scale`
            // (the normalisation); the reciprocal must carry it too.
            values.push(Complex64::new(scale * scale, 0.0) / v);
        }
        Some(KernelSpectrum { values })
    }

    /// Smallest real part of the spectrum (positive for a positive-definite embedding).
    pub fn min_real(&self) -> f64 {
        self.values
            .iter()
            .map(|v| v.re)
            .fold(f64::INFINITY, f64::min)
    }
}

/// Zero-padded FFT convolution on an `nx × ny` grid: plans, buffers and scratch.
pub struct FftConvolution {
    nx: usize,
    ny: usize,
    /// Length of the padded rows, 2nx.
    mx: usize,
    /// Length of the padded columns, 2ny.
    my: usize,
    /// Complex length of a row spectrum, nx + 1.
    kx: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
    rows: Vec<f64>,
    row_spectra: Vec<Complex64>,
    columns: Vec<Complex64>,
    /// Second column buffer of [`FftConvolution::apply_block`].
    columns2: Vec<Complex64>,
    row_scratch: Vec<Complex64>,
    col_scratch: Vec<Complex64>,
    /// Whether each input row of the last forward pass held a non-zero value.
    row_used: Vec<bool>,
    tasks: usize,
    row_scratch_len: usize,
    col_scratch_len: usize,
}

impl std::fmt::Debug for FftConvolution {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FftConvolution")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("tasks", &self.tasks)
            .finish()
    }
}

impl FftConvolution {
    /// Plan the transforms and allocate all buffers for an `nx × ny` grid.
    pub fn new(nx: usize, ny: usize) -> Self {
        let (mx, my, kx) = (2 * nx, 2 * ny, nx + 1);
        let mut real_planner = RealFftPlanner::<f64>::new();
        let r2c = real_planner.plan_fft_forward(mx);
        let c2r = real_planner.plan_fft_inverse(mx);
        let mut planner = FftPlanner::<f64>::new();
        let col_forward = planner.plan_fft_forward(my);
        let col_inverse = planner.plan_fft_inverse(my);
        let tasks = if nx * ny >= PARALLEL_THRESHOLD {
            rayon::current_num_threads().max(1)
        } else {
            1
        };
        let row_scratch_len = r2c.get_scratch_len().max(c2r.get_scratch_len()).max(1);
        let col_scratch_len = col_forward
            .get_inplace_scratch_len()
            .max(col_inverse.get_inplace_scratch_len())
            .max(1);
        FftConvolution {
            nx,
            ny,
            mx,
            my,
            kx,
            r2c,
            c2r,
            col_forward,
            col_inverse,
            rows: vec![0.0; ny * mx],
            row_spectra: vec![Complex64::default(); ny * kx],
            columns: vec![Complex64::default(); kx * my],
            columns2: Vec::new(),
            row_scratch: vec![Complex64::default(); tasks * row_scratch_len],
            col_scratch: vec![Complex64::default(); tasks * col_scratch_len],
            row_used: vec![false; ny],
            tasks,
            row_scratch_len,
            col_scratch_len,
        }
    }

    /// Grid size (nx, ny).
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// Spectrum of a kernel tabulated in circulant order on the `2nx × 2ny` embedding
    /// (x fastest; see [`crate::influence::circulant_kernel`]). Done once per grid.
    pub fn kernel_spectrum(&self, kernel: &[f64]) -> KernelSpectrum {
        assert_eq!(kernel.len(), self.mx * self.my, "kernel must be 2nx × 2ny");
        let mut planner = RealFftPlanner::<f64>::new();
        let r2c = planner.plan_fft_forward(self.mx);
        let mut row = vec![0.0; self.mx];
        let mut row_spec = vec![Complex64::default(); self.kx];
        let mut values = vec![Complex64::default(); self.kx * self.my];
        for j in 0..self.my {
            row.copy_from_slice(&kernel[j * self.mx..(j + 1) * self.mx]);
            r2c.process(&mut row, &mut row_spec)
                .expect("buffer lengths are set from the plan");
            for (k, &v) in row_spec.iter().enumerate() {
                values[k * self.my + j] = v;
            }
        }
        let mut scratch = vec![Complex64::default(); self.col_scratch_len];
        self.col_forward
            .process_with_scratch(&mut values, &mut scratch);
        let scale = self.normalisation();
        for v in &mut values {
            *v *= scale;
        }
        KernelSpectrum { values }
    }

    /// The inverse-FFT normalisation 1/(4 nx ny) carried by stored spectra.
    pub fn normalisation(&self) -> f64 {
        1.0 / (self.mx * self.my) as f64
    }

    /// `output = K * input` (linear, non-periodic convolution on the grid) for the kernel
    /// whose spectrum is given. `input` and `output` have `nx·ny` values. No allocation.
    pub fn apply(&mut self, spectrum: &KernelSpectrum, input: &[f64], output: &mut [f64]) {
        let ny = self.ny;
        self.apply_rows(spectrum, input, output, 0..ny);
    }

    /// [`Self::apply`] computing only the output rows `rows` (row iy holds the elements
    /// `iy·nx .. (iy + 1)·nx`); the other rows of `output` are set to zero. Every computed
    /// value equals that of [`Self::apply`] bit for bit: the rows skipped are those of the
    /// last (inverse) row transforms, each of which is independent of the others.
    /// Panics if `rows` does not lie within `0..ny`.
    pub fn apply_rows(
        &mut self,
        spectrum: &KernelSpectrum,
        input: &[f64],
        output: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        let (nx, my, kx) = (self.nx, self.my, self.kx);
        assert!(
            rows.start <= rows.end && rows.end <= self.ny,
            "output rows within the grid"
        );
        assert_eq!(input.len(), nx * self.ny);
        assert_eq!(output.len(), nx * self.ny);
        assert_eq!(spectrum.values.len(), kx * my);
        let mut columns = std::mem::take(&mut self.columns);
        self.rows_to_columns(input, &mut columns);
        // 3. Column transforms, kernel multiplication, inverse column transforms.
        let cols_per_task = kx.div_ceil(self.tasks);
        let (fwd, inv) = (&self.col_forward, &self.col_inverse);
        let kernel = &spectrum.values;
        columns
            .par_chunks_mut(cols_per_task * my)
            .zip(kernel.par_chunks(cols_per_task * my))
            .zip(self.col_scratch.par_chunks_mut(self.col_scratch_len))
            .with_max_len(1)
            .for_each(|((cols, kern), scratch)| {
                fwd.process_with_scratch(cols, scratch);
                for (v, k) in cols.iter_mut().zip(kern) {
                    *v *= *k;
                }
                inv.process_with_scratch(cols, scratch);
            });
        self.columns_to_rows(&columns, output, rows);
        self.columns = columns;
    }

    /// The 2 × 2 block product of a symmetric kernel block \[\[xx, xy\], \[xy, yy\]\]:
    /// `out_x = K_xx * in_x + K_xy * in_y`, `out_y = K_xy * in_x + K_yy * in_y`, with one
    /// forward transform per input and one inverse per output (4 transforms instead of the 8
    /// of four [`Self::apply`] calls). Allocates its second buffer on first use only.
    pub fn apply_block(
        &mut self,
        [kxx, kxy, kyy]: [&KernelSpectrum; 3],
        (in_x, in_y): (&[f64], &[f64]),
        (out_x, out_y): (&mut [f64], &mut [f64]),
    ) {
        let (nx, my, kx) = (self.nx, self.my, self.kx);
        for v in [in_x, in_y, &*out_x, &*out_y] {
            assert_eq!(v.len(), nx * self.ny);
        }
        for k in [kxx, kxy, kyy] {
            assert_eq!(k.values.len(), kx * my);
        }
        let mut a = std::mem::take(&mut self.columns);
        let mut b = std::mem::take(&mut self.columns2);
        b.resize(kx * my, Complex64::default());
        self.rows_to_columns(in_x, &mut a);
        self.rows_to_columns(in_y, &mut b);
        let cols_per_task = kx.div_ceil(self.tasks);
        let (fwd, inv) = (&self.col_forward, &self.col_inverse);
        let chunk = cols_per_task * my;
        a.par_chunks_mut(chunk)
            .zip(b.par_chunks_mut(chunk))
            .zip(kxx.values.par_chunks(chunk))
            .zip(kxy.values.par_chunks(chunk))
            .zip(kyy.values.par_chunks(chunk))
            .zip(self.col_scratch.par_chunks_mut(self.col_scratch_len))
            .with_max_len(1)
            .for_each(|(((((ca, cb), xx), xy), yy), scratch)| {
                fwd.process_with_scratch(ca, scratch);
                fwd.process_with_scratch(cb, scratch);
                for ((((u, v), xx), xy), yy) in
                    ca.iter_mut().zip(cb.iter_mut()).zip(xx).zip(xy).zip(yy)
                {
                    let (p, q) = (*u, *v);
                    *u = xx * p + xy * q;
                    *v = xy * p + yy * q;
                }
                inv.process_with_scratch(ca, scratch);
                inv.process_with_scratch(cb, scratch);
            });
        let ny = self.ny;
        self.columns_to_rows(&a, out_x, 0..ny);
        self.columns_to_rows(&b, out_y, 0..ny);
        self.columns = a;
        self.columns2 = b;
    }

    /// Steps 1–2 of the module documentation: pad and transform the rows of `input`, scatter
    /// the row spectra into `columns` (zero rows ny..2ny are the padding). An input row that
    /// is zero (e.g. outside the contact set) is not transformed (its spectrum is zero), and
    /// only the band of rows between the first and the last non-zero one is scattered.
    fn rows_to_columns(&mut self, input: &[f64], columns: &mut [Complex64]) {
        let (nx, mx, my, kx) = (self.nx, self.mx, self.my, self.kx);
        let rows_per_task = self.ny.div_ceil(self.tasks);
        // 1. Pad and transform the non-zero rows.
        let r2c = &self.r2c;
        self.rows
            .par_chunks_mut(rows_per_task * mx)
            .zip(self.row_spectra.par_chunks_mut(rows_per_task * kx))
            .zip(input.par_chunks(rows_per_task * nx))
            .zip(self.row_scratch.par_chunks_mut(self.row_scratch_len))
            .zip(self.row_used.par_chunks_mut(rows_per_task))
            .with_max_len(1)
            .for_each(|((((rows, specs), inp), scratch), used)| {
                for (((row, spec), src), used) in rows
                    .chunks_mut(mx)
                    .zip(specs.chunks_mut(kx))
                    .zip(inp.chunks(nx))
                    .zip(used.iter_mut())
                {
                    *used = src.iter().any(|&x| x != 0.0);
                    if !*used {
                        continue;
                    }
                    row[..nx].copy_from_slice(src);
                    row[nx..].fill(0.0);
                    r2c.process_with_scratch(row, spec, scratch)
                        .expect("buffer lengths are set from the plan");
                }
            });
        let lo = self.row_used.iter().position(|&u| u).unwrap_or(0);
        let hi = self.row_used.iter().rposition(|&u| u).map_or(0, |j| j + 1);
        // Zero rows inside the band: their spectra are zero.
        for j in lo..hi {
            if !self.row_used[j] {
                self.row_spectra[j * kx..(j + 1) * kx].fill(Complex64::default());
            }
        }

        // 2. Scatter row spectra lo..hi into columns (all other entries are zero). A tiled
        //    transpose keeps both the strided reads and the writes in cache.
        let row_spectra = &self.row_spectra;
        let cols_per_task = kx.div_ceil(self.tasks);
        columns
            .par_chunks_mut(cols_per_task * my)
            .enumerate()
            .with_max_len(1)
            .for_each(|(task, cols)| {
                let first = task * cols_per_task;
                let count = cols.len() / my;
                for j0 in (lo..hi).step_by(TILE) {
                    let j1 = (j0 + TILE).min(hi);
                    for c in 0..count {
                        let k = first + c;
                        let col = &mut cols[c * my + j0..c * my + j1];
                        // Strided read without per-element bounds checks.
                        for (v, s) in col
                            .iter_mut()
                            .zip(row_spectra[j0 * kx + k..].iter().step_by(kx))
                        {
                            *v = *s;
                        }
                    }
                }
                for col in cols.chunks_mut(my) {
                    col[..lo].fill(Complex64::default());
                    col[hi.max(lo)..].fill(Complex64::default());
                }
            });
    }

    /// Step 4 of the module documentation: gather the output rows `rows` of `columns` (after
    /// the inverse column transforms) and transform them back into `output`; the other rows
    /// of `output` are set to zero.
    fn columns_to_rows(
        &mut self,
        columns: &[Complex64],
        output: &mut [f64],
        rows: std::ops::Range<usize>,
    ) {
        let (nx, mx, my, kx) = (self.nx, self.mx, self.my, self.kx);
        let (lo, hi) = (rows.start, rows.end);
        output[..lo * nx].fill(0.0);
        output[hi * nx..].fill(0.0);
        if hi == lo {
            return;
        }
        let rows_per_task = (hi - lo).div_ceil(self.tasks);
        // 4. Gather the kept rows (tiled transpose) and transform them back.
        self.row_spectra[lo * kx..hi * kx]
            .par_chunks_mut(rows_per_task * kx)
            .enumerate()
            .with_max_len(1)
            .for_each(|(task, specs)| {
                let first = lo + task * rows_per_task;
                let count = specs.len() / kx;
                for k0 in (0..kx).step_by(TILE) {
                    let k1 = (k0 + TILE).min(kx);
                    for r in 0..count {
                        let j = first + r;
                        let spec = &mut specs[r * kx + k0..r * kx + k1];
                        for (v, s) in spec
                            .iter_mut()
                            .zip(columns[k0 * my + j..].iter().step_by(my))
                        {
                            *v = *s;
                        }
                    }
                }
            });
        let c2r = &self.c2r;
        self.row_spectra[lo * kx..hi * kx]
            .par_chunks_mut(rows_per_task * kx)
            .zip(self.rows[lo * mx..hi * mx].par_chunks_mut(rows_per_task * mx))
            .zip(output[lo * nx..hi * nx].par_chunks_mut(rows_per_task * nx))
            .zip(self.row_scratch.par_chunks_mut(self.row_scratch_len))
            .with_max_len(1)
            .for_each(|(((specs, rows), out), scratch)| {
                for ((spec, row), dst) in specs
                    .chunks_mut(kx)
                    .zip(rows.chunks_mut(mx))
                    .zip(out.chunks_mut(nx))
                {
                    // A real signal has real DC and Nyquist coefficients; drop round-off.
                    spec[0].im = 0.0;
                    spec[kx - 1].im = 0.0;
                    c2r.process_with_scratch(spec, row, scratch)
                        .expect("spectrum is real at DC and Nyquist");
                    dst.copy_from_slice(&row[..nx]);
                }
            });
    }
}
