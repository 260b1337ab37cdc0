//! The tangential influence operators: the kernels of [`crate::TangentialSolver`] behind one
//! trait, with the FFT implementation and the direct O(n²) oracle.
//!
//! The tangential solver works with three kernels of the coefficients of
//! [`crate::influence::tangential_influence`] (references.md §C3.2, §C3.5), each a 2 × 2
//! traction block (xx, xy, yy) plus, for dissimilar materials (K ≠ 0), the coupling
//! column (xn, yn):
//!
//! * [`TangentialKernel::Direct`]: A, observation points at the element centres (shift,
//!   transient steps);
//! * [`TangentialKernel::Steady`]: A − A_v(δx) with δx = dx, the operator of steady rolling;
//! * [`TangentialKernel::Shifted`]: A_v(δq), the observation points moved by δq along x
//!   (CONTACT's kernel C_v: the displacement the particles had one step earlier).
//!
//! [`FftTangentialInfluence`] tabulates each kernel once (the steady and shifted ones on first
//! use, [`TangentialInfluenceOperator::prepare`]) and applies it by zero-padded FFT
//! convolution; [`DirectTangentialInfluence`] sums the closed-form coefficients pair by pair
//! with no table and no FFT.

use crate::convolution::{FftConvolution, KernelSpectrum};
use crate::error::{ContactError, positive};
use crate::grid::Grid;
use crate::influence::{
    Component, TangentialInfluence, circulant_from_centred, tangential_influence,
    tangential_offset_tables,
};
use crate::material::Material;

/// Which kernel of the tangential family (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TangentialKernel {
    /// A: shift problems and transient steps.
    Direct,
    /// A − A_v(δx), δx = the grid's dx: steady rolling.
    Steady,
    /// A_v(δq) for the distance δq \[m\] rolled in a transient step.
    Shifted(f64),
}

/// Whether a product overwrites its output or is subtracted from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Update {
    /// out = K p.
    Set,
    /// out −= K p.
    Subtract,
}

/// The products the tangential solver needs. Slices hold one value per element (x fastest);
/// tractions and pressures in Pa, displacements in m. A kernel must be
/// [`prepare`](Self::prepare)d before it is used (for [`TangentialKernel::Shifted`]: with
/// the same δq).
pub trait TangentialInfluenceOperator {
    /// The grid the operator acts on.
    fn grid(&self) -> &Grid;

    /// The combined material.
    fn material(&self) -> &Material;

    /// Make `kernel` ready (tabulate and transform it on first use; plan once).
    fn prepare(&mut self, kernel: TangentialKernel);

    /// u_x = C_xx p_x + C_xy p_y, u_y = C_xy p_x + C_yy p_y, written or subtracted.
    fn traction_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        traction: (&[f64], &[f64]),
        out: (&mut [f64], &mut [f64]),
    );

    /// u_x = C_xn p_n, u_y = C_yn p_n (the pressure's own tangential displacement; zero for
    /// K = 0), written or subtracted.
    fn pressure_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        pressure: &[f64],
        out: (&mut [f64], &mut [f64]),
    );

    /// u_n = A_nx p_x + A_ny p_y = −(A_xn p_x + A_yn p_y) of the direct kernel (zero for K = 0).
    fn normal_from_traction(&mut self, traction: (&[f64], &[f64]), out: &mut [f64]);

    /// (C_xx, C_yy) of an element on itself (C_xy vanishes there by symmetry).
    fn own_coefficients(&self, kernel: TangentialKernel) -> (f64, f64);

    /// (A_xx, A_xy, A_yy) of the direct kernel A at the element offset (o_x, o_y) =
    /// observation − loaded element, |o_x| ≤ nx (one element beyond the grid) and |o_y| < ny:
    /// read from the kernel table where it holds the offset, else from the closed form.
    fn direct_coefficient(&self, offset: (isize, isize)) -> (f64, f64, f64);

    /// S += C e_J Δ: the column of element J = `element` (ix, iy) times the traction change
    /// Δ = `change`, over the observation box `columns` = (ix0, ix1) × `rows` = (iy0, iy1)
    /// (inclusive). Called once per element per sweep: no allocation.
    fn add_column(
        &self,
        kernel: TangentialKernel,
        element: (usize, usize),
        change: (f64, f64),
        out: (&mut [f64], &mut [f64]),
        columns: (usize, usize),
        rows: (usize, usize),
    );
}

/// The traction block (xx, xy, yy) of one kernel: centred offset tables (for columns) and
/// FFT spectra (for products).
#[derive(Debug)]
struct KernelSet {
    xx: Vec<f64>,
    xy: Vec<f64>,
    yy: Vec<f64>,
    spectra: [KernelSpectrum; 3],
}

impl KernelSet {
    fn new(conv: &FftConvolution, grid: &Grid, tables: [Vec<f64>; 3]) -> Self {
        let spectra = [
            conv.kernel_spectrum(&circulant_from_centred(grid, &tables[0])),
            conv.kernel_spectrum(&circulant_from_centred(grid, &tables[1])),
            conv.kernel_spectrum(&circulant_from_centred(grid, &tables[2])),
        ];
        let [xx, xy, yy] = tables;
        KernelSet {
            xx,
            xy,
            yy,
            spectra,
        }
    }
}

const TRACTION: [Component; 3] = [Component::Xx, Component::Xy, Component::Yy];
const COUPLING: [Component; 2] = [Component::Xn, Component::Yn];

/// Centred tables of `components` with the observation points shifted by `shift`, minus the
/// same with `minus_shift` when given (A − A_v of steady rolling).
fn tables(
    material: &Material,
    grid: &Grid,
    shift: f64,
    minus_shift: Option<f64>,
    components: &[Component],
) -> Vec<Vec<f64>> {
    let a = tangential_offset_tables(material, grid, shift, components);
    match minus_shift {
        None => a,
        Some(s) => {
            let v = tangential_offset_tables(material, grid, s, components);
            a.iter()
                .zip(&v)
                .map(|(a, v)| a.iter().zip(v).map(|(a, v)| a - v).collect())
                .collect()
        }
    }
}

/// The steady tables A − A_v(δx) of `components` from the centred tables `direct` of A
/// (shift 0): A_v(δx) at offset o is A at o + (1, 0), read from `direct` one column to the
/// right, so only the last column (o_x = nx) is evaluated anew. The same values as
/// `tables(…, 0.0, Some(dx), …)` (the offset o_x·dx + dx there against (o_x + 1)·dx here: a
/// rounding difference), at a third of the cost.
fn steady_from_direct(
    material: &Material,
    grid: &Grid,
    direct: &[&[f64]],
    components: &[Component],
) -> Vec<Vec<f64>> {
    let (wx, wy) = (2 * grid.nx - 1, 2 * grid.ny - 1);
    let mut out: Vec<Vec<f64>> = direct.iter().map(|d| d.to_vec()).collect();
    for j in 0..wy {
        let oy = (j as f64 - (grid.ny as f64 - 1.0)) * grid.dy;
        let edge = tangential_influence(material, grid.nx as f64 * grid.dx, oy, grid.dx, grid.dy);
        for (table, &c) in out.iter_mut().zip(components) {
            let row = &mut table[j * wx..(j + 1) * wx];
            for i in 0..wx - 1 {
                row[i] -= row[i + 1];
            }
            row[wx - 1] -= edge.get(c);
        }
    }
    out
}

/// The FFT implementation (module documentation). No product allocates.
#[derive(Debug)]
pub struct FftTangentialInfluence {
    grid: Grid,
    material: Material,
    conv: FftConvolution,
    direct: KernelSet,
    steady: Option<KernelSet>,
    shifted: Option<(f64, KernelSet)>,
    /// Coupling spectra (xn, yn), K ≠ 0 only: direct, steady, shifted.
    coupling: Option<[KernelSpectrum; 2]>,
    coupling_steady: Option<[KernelSpectrum; 2]>,
    coupling_shifted: Option<(f64, [KernelSpectrum; 2])>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
}

impl FftTangentialInfluence {
    /// Tabulate A_xx, A_xy, A_yy (and A_xn, A_yn for K ≠ 0) for `grid` and plan the FFTs.
    pub fn new(grid: Grid, material: &Material) -> Result<Self, ContactError> {
        let grid = Grid::new(grid.nx, grid.ny, grid.dx, grid.dy, grid.x0, grid.y0)?;
        positive("G", material.g)?;
        let conv = FftConvolution::new(grid.nx, grid.ny);
        let t = tables(material, &grid, 0.0, None, &TRACTION);
        let direct = KernelSet::new(&conv, &grid, t.try_into().expect("three components"));
        let coupling = (material.k != 0.0).then(|| {
            let t = tables(material, &grid, 0.0, None, &COUPLING);
            Self::coupling_spectra(&conv, &grid, &t)
        });
        Ok(Self {
            grid,
            material: *material,
            conv,
            direct,
            steady: None,
            shifted: None,
            coupling,
            coupling_steady: None,
            coupling_shifted: None,
            tmp: vec![0.0; grid.len()],
            tmp2: vec![0.0; grid.len()],
        })
    }

    fn coupling_spectra(conv: &FftConvolution, grid: &Grid, t: &[Vec<f64>]) -> [KernelSpectrum; 2] {
        [
            conv.kernel_spectrum(&circulant_from_centred(grid, &t[0])),
            conv.kernel_spectrum(&circulant_from_centred(grid, &t[1])),
        ]
    }
}

/// The traction block of a prepared kernel (a free function over the fields, so that the
/// plans can be borrowed mutably at the same time).
fn block<'a>(
    direct: &'a KernelSet,
    steady: &'a Option<KernelSet>,
    shifted: &'a Option<(f64, KernelSet)>,
    kernel: TangentialKernel,
) -> &'a KernelSet {
    match kernel {
        TangentialKernel::Direct => direct,
        TangentialKernel::Steady => steady.as_ref().expect("steady kernel prepared"),
        TangentialKernel::Shifted(d) => match shifted {
            Some((s, k)) if *s == d => k,
            _ => panic!("shifted kernel for δq = {d} not prepared"),
        },
    }
}

/// out (= or −=) K p by FFT, through `tmp` when subtracting.
fn convolve(
    conv: &mut FftConvolution,
    spectrum: &KernelSpectrum,
    update: Update,
    input: &[f64],
    out: &mut [f64],
    tmp: &mut [f64],
) {
    match update {
        Update::Set => conv.apply(spectrum, input, out),
        Update::Subtract => {
            conv.apply(spectrum, input, tmp);
            sub(out, tmp);
        }
    }
}

/// (A_xx, A_xy, A_yy) at the element offset `offset` of `grid` from the closed form.
fn closed_form(material: &Material, grid: &Grid, (ox, oy): (isize, isize)) -> (f64, f64, f64) {
    let t = tangential_influence(
        material,
        ox as f64 * grid.dx,
        oy as f64 * grid.dy,
        grid.dx,
        grid.dy,
    );
    (t.xx, t.xy, t.yy)
}

fn sub(a: &mut [f64], b: &[f64]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x -= y;
    }
}

impl TangentialInfluenceOperator for FftTangentialInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn material(&self) -> &Material {
        &self.material
    }

    fn prepare(&mut self, kernel: TangentialKernel) {
        let (g, m) = (self.grid, self.material);
        match kernel {
            TangentialKernel::Direct => {}
            TangentialKernel::Steady => {
                if self.steady.is_none() {
                    let d = &self.direct;
                    let direct = [d.xx.as_slice(), d.xy.as_slice(), d.yy.as_slice()];
                    let t = steady_from_direct(&m, &g, &direct, &TRACTION);
                    let set = KernelSet::new(&self.conv, &g, t.try_into().expect("three"));
                    self.steady = Some(set);
                }
                if self.coupling.is_some() && self.coupling_steady.is_none() {
                    let t = tables(&m, &g, 0.0, Some(g.dx), &COUPLING);
                    self.coupling_steady = Some(Self::coupling_spectra(&self.conv, &g, &t));
                }
            }
            TangentialKernel::Shifted(d) => {
                if let Some((s, _)) = &self.shifted
                    && *s == d
                {
                    return;
                }
                let t = tables(&m, &g, d, None, &TRACTION);
                let set = KernelSet::new(&self.conv, &g, t.try_into().expect("three"));
                self.shifted = Some((d, set));
                if self.coupling.is_some() {
                    let t = tables(&m, &g, d, None, &COUPLING);
                    self.coupling_shifted = Some((d, Self::coupling_spectra(&self.conv, &g, &t)));
                }
            }
        }
    }

    fn traction_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        (px, py): (&[f64], &[f64]),
        (ux, uy): (&mut [f64], &mut [f64]),
    ) {
        let set = block(&self.direct, &self.steady, &self.shifted, kernel);
        let [kxx, kxy, kyy] = &set.spectra;
        let spectra = [kxx, kxy, kyy];
        match update {
            Update::Set => self.conv.apply_block(spectra, (px, py), (ux, uy)),
            Update::Subtract => {
                let (tx, ty) = (&mut self.tmp, &mut self.tmp2);
                self.conv.apply_block(spectra, (px, py), (tx, ty));
                sub(ux, tx);
                sub(uy, ty);
            }
        }
    }

    fn pressure_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        pressure: &[f64],
        (ux, uy): (&mut [f64], &mut [f64]),
    ) {
        let Some(direct) = &self.coupling else {
            // K = 0: the pressure has no tangential displacement.
            if update == Update::Set {
                ux.fill(0.0);
                uy.fill(0.0);
            }
            return;
        };
        let [kx, ky] = match kernel {
            TangentialKernel::Direct => direct,
            TangentialKernel::Steady => self.coupling_steady.as_ref().expect("prepared"),
            TangentialKernel::Shifted(d) => match &self.coupling_shifted {
                Some((s, k)) if *s == d => k,
                _ => panic!("shifted coupling kernel for δq = {d} not prepared"),
            },
        };
        convolve(&mut self.conv, kx, update, pressure, ux, &mut self.tmp);
        convolve(&mut self.conv, ky, update, pressure, uy, &mut self.tmp);
    }

    fn normal_from_traction(&mut self, (px, py): (&[f64], &[f64]), out: &mut [f64]) {
        match &self.coupling {
            None => out.fill(0.0),
            Some([kxn, kyn]) => {
                self.conv.apply(kxn, px, out);
                self.conv.apply(kyn, py, &mut self.tmp);
                for (o, t) in out.iter_mut().zip(&self.tmp) {
                    *o = -(*o + t);
                }
            }
        }
    }

    fn own_coefficients(&self, kernel: TangentialKernel) -> (f64, f64) {
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let centre = (ny - 1) * (2 * nx - 1) + (nx - 1);
        let set = block(&self.direct, &self.steady, &self.shifted, kernel);
        (set.xx[centre], set.yy[centre])
    }

    fn direct_coefficient(&self, (ox, oy): (isize, isize)) -> (f64, f64, f64) {
        let (nx, ny) = (self.grid.nx as isize, self.grid.ny as isize);
        if ox.abs() < nx && oy.abs() < ny {
            let i = ((oy + ny - 1) * (2 * nx - 1) + ox + nx - 1) as usize;
            let d = &self.direct;
            (d.xx[i], d.xy[i], d.yy[i])
        } else {
            closed_form(&self.material, &self.grid, (ox, oy))
        }
    }

    /// Reads contiguous rows of the centred tables.
    fn add_column(
        &self,
        kernel: TangentialKernel,
        (jx, jy): (usize, usize),
        (ddx, ddy): (f64, f64),
        (sx, sy): (&mut [f64], &mut [f64]),
        (ix0, ix1): (usize, usize),
        (iy0, iy1): (usize, usize),
    ) {
        let k = block(&self.direct, &self.steady, &self.shifted, kernel);
        let (nx, ny) = (self.grid.nx, self.grid.ny);
        let wx = 2 * nx - 1;
        let len = ix1 + 1 - ix0;
        for iy in iy0..=iy1 {
            let start = (iy + ny - 1 - jy) * wx + (nx - 1 - jx) + ix0;
            let kxx = &k.xx[start..start + len];
            let kxy = &k.xy[start..start + len];
            let kyy = &k.yy[start..start + len];
            let row = iy * nx + ix0;
            let rx = &mut sx[row..row + len];
            for ((s, a), b) in rx.iter_mut().zip(kxx).zip(kxy) {
                *s += a * ddx + b * ddy;
            }
            let ry = &mut sy[row..row + len];
            for ((s, a), b) in ry.iter_mut().zip(kxy).zip(kyy) {
                *s += a * ddx + b * ddy;
            }
        }
    }
}

/// The direct O(n²) sums of the closed-form coefficients (module documentation): every
/// coefficient evaluated from [`tangential_influence`] at the offset of the two elements.
#[derive(Debug, Clone)]
pub struct DirectTangentialInfluence {
    grid: Grid,
    material: Material,
}

impl DirectTangentialInfluence {
    /// The oracle on `grid` for `material`.
    pub fn new(grid: Grid, material: Material) -> Result<Self, ContactError> {
        let grid = Grid::new(grid.nx, grid.ny, grid.dx, grid.dy, grid.x0, grid.y0)?;
        positive("G", material.g)?;
        Ok(Self { grid, material })
    }

    /// All coefficients of `kernel` for observation element `i` and loaded element `j`.
    pub fn coefficients(
        &self,
        kernel: TangentialKernel,
        i: usize,
        j: usize,
    ) -> TangentialInfluence {
        let g = &self.grid;
        let ((xi, yi), (xj, yj)) = (g.centre(i), g.centre(j));
        let at =
            |shift: f64| tangential_influence(&self.material, xi - xj + shift, yi - yj, g.dx, g.dy);
        match kernel {
            TangentialKernel::Direct => at(0.0),
            TangentialKernel::Shifted(d) => at(d),
            TangentialKernel::Steady => {
                let (a, v) = (at(0.0), at(g.dx));
                TangentialInfluence {
                    xx: a.xx - v.xx,
                    xy: a.xy - v.xy,
                    yy: a.yy - v.yy,
                    xn: a.xn - v.xn,
                    yn: a.yn - v.yn,
                }
            }
        }
    }

    /// (out_x, out_y)_I (= or −=) Σ_J f(C_IJ) with f giving the pair's two contributions.
    fn sum(
        &self,
        kernel: TangentialKernel,
        update: Update,
        (ux, uy): (&mut [f64], &mut [f64]),
        f: impl Fn(&TangentialInfluence, usize) -> (f64, f64),
    ) {
        let n = self.grid.len();
        assert!(ux.len() == n && uy.len() == n, "one value per element");
        for i in 0..n {
            let (mut sx, mut sy) = (0.0, 0.0);
            for j in 0..n {
                let (a, b) = f(&self.coefficients(kernel, i, j), j);
                sx += a;
                sy += b;
            }
            match update {
                Update::Set => (ux[i], uy[i]) = (sx, sy),
                Update::Subtract => {
                    ux[i] -= sx;
                    uy[i] -= sy;
                }
            }
        }
    }
}

impl TangentialInfluenceOperator for DirectTangentialInfluence {
    fn grid(&self) -> &Grid {
        &self.grid
    }

    fn material(&self) -> &Material {
        &self.material
    }

    /// Nothing to tabulate.
    fn prepare(&mut self, _kernel: TangentialKernel) {}

    fn traction_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        (px, py): (&[f64], &[f64]),
        out: (&mut [f64], &mut [f64]),
    ) {
        self.sum(kernel, update, out, |c, j| {
            (c.xx * px[j] + c.xy * py[j], c.xy * px[j] + c.yy * py[j])
        });
    }

    fn pressure_product(
        &mut self,
        kernel: TangentialKernel,
        update: Update,
        pressure: &[f64],
        out: (&mut [f64], &mut [f64]),
    ) {
        self.sum(kernel, update, out, |c, j| {
            (c.xn * pressure[j], c.yn * pressure[j])
        });
    }

    fn normal_from_traction(&mut self, (px, py): (&[f64], &[f64]), out: &mut [f64]) {
        let n = self.grid.len();
        assert_eq!(out.len(), n, "one value per element");
        for (i, o) in out.iter_mut().enumerate() {
            *o = -(0..n)
                .map(|j| {
                    let c = self.coefficients(TangentialKernel::Direct, i, j);
                    c.xn * px[j] + c.yn * py[j]
                })
                .sum::<f64>();
        }
    }

    fn direct_coefficient(&self, offset: (isize, isize)) -> (f64, f64, f64) {
        closed_form(&self.material, &self.grid, offset)
    }

    fn own_coefficients(&self, kernel: TangentialKernel) -> (f64, f64) {
        let c = self.coefficients(kernel, 0, 0);
        (c.xx, c.yy)
    }

    fn add_column(
        &self,
        kernel: TangentialKernel,
        (jx, jy): (usize, usize),
        (ddx, ddy): (f64, f64),
        (sx, sy): (&mut [f64], &mut [f64]),
        (ix0, ix1): (usize, usize),
        (iy0, iy1): (usize, usize),
    ) {
        let nx = self.grid.nx;
        let j = jy * nx + jx;
        for iy in iy0..=iy1 {
            for ix in ix0..=ix1 {
                let i = iy * nx + ix;
                let c = self.coefficients(kernel, i, j);
                sx[i] += c.xx * ddx + c.xy * ddy;
                sy[i] += c.xy * ddx + c.yy * ddy;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The steady tables read from the direct ones equal the two tabulations A(o) − A(o + δx)
    /// (the closed-form coefficients evaluated at both offsets), on a grid with dx ≠ dy.
    #[test]
    fn steady_tables_from_the_direct_ones_equal_two_tabulations() {
        let m = Material::from_combined(82e9, 0.28).unwrap();
        let g = Grid::new(7, 5, 0.3e-3, 0.5e-3, -1e-3, 2e-3).unwrap();
        let direct = tables(&m, &g, 0.0, None, &TRACTION);
        let refs: Vec<&[f64]> = direct.iter().map(|t| t.as_slice()).collect();
        let fast = steady_from_direct(&m, &g, &refs, &TRACTION);
        let slow = tables(&m, &g, 0.0, Some(g.dx), &TRACTION);
        for (c, (f, s)) in fast.iter().zip(&slow).enumerate() {
            let scale = direct[c].iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            assert!(scale > 0.0);
            for (k, (a, b)) in f.iter().zip(s).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-13 * scale,
                    "component {c}, offset {k}: {a} {b}"
                );
            }
        }
    }
}
