//! Influence tables and FFT spectra of the tangential operators: A (shift, transient),
//! A − A_v(δx) (steady rolling), A_v(δq) (transient), and the coupling kernels A_xn, A_yn
//! (K ≠ 0); dense column updates of the shift.

use super::TangentialSolver;
use crate::convolution::{FftConvolution, KernelSpectrum};
use crate::grid::Grid;
use crate::influence::{Component, circulant_from_centred, tangential_offset_tables};

/// Centred offset tables and FFT spectra of one tangential operator (xx, xy, yy).
#[derive(Debug)]
pub(super) struct KernelSet {
    pub(super) xx: Vec<f64>,
    pub(super) xy: Vec<f64>,
    pub(super) yy: Vec<f64>,
    pub(super) spectra: [KernelSpectrum; 3],
}

impl KernelSet {
    pub(super) fn new(conv: &FftConvolution, grid: &Grid, tables: [Vec<f64>; 3]) -> Self {
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

/// Which coupling term enters W (K ≠ 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Coupling {
    /// A_tn p_n (a shift from the unloaded state).
    Direct,
    /// (A_tn − A_v,tn(δx)) p_n (steady rolling).
    Steady,
    /// A_tn p_n − A_v,tn(δq) p_n' (a transient rolling step).
    Shifted,
}

/// Which operator C the Gauss–Seidel iteration uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Operator {
    /// C = A (shift and transient steps).
    Direct,
    /// C = A − A_v(δx) (steady rolling).
    Steady,
}

pub(super) const COMPONENTS: [Component; 3] = [Component::Xx, Component::Xy, Component::Yy];

impl TangentialSolver {
    pub(super) fn ensure_steady(&mut self) {
        if self.steady.is_none() {
            let g = self.grid;
            let a = tangential_offset_tables(&self.material, &g, 0.0, &COMPONENTS);
            let v = tangential_offset_tables(&self.material, &g, g.dx, &COMPONENTS);
            let diff: Vec<Vec<f64>> = a
                .iter()
                .zip(&v)
                .map(|(a, v)| a.iter().zip(v).map(|(a, v)| a - v).collect())
                .collect();
            let tables: [Vec<f64>; 3] = diff.try_into().expect("three components");
            self.steady = Some(KernelSet::new(&self.conv, &g, tables));
        }
        if self.coupling.is_some() && self.coupling_steady.is_none() {
            let g = self.grid;
            let c = [Component::Xn, Component::Yn];
            let a = tangential_offset_tables(&self.material, &g, 0.0, &c);
            let v = tangential_offset_tables(&self.material, &g, g.dx, &c);
            let spec = |k: usize| {
                let d: Vec<f64> = a[k].iter().zip(&v[k]).map(|(a, v)| a - v).collect();
                self.conv.kernel_spectrum(&circulant_from_centred(&g, &d))
            };
            self.coupling_steady = Some([spec(0), spec(1)]);
        }
    }

    pub(super) fn ensure_shifted(&mut self, delta_q: f64) {
        if let Some((d, _)) = &self.shifted
            && *d == delta_q
        {
            return;
        }
        let g = self.grid;
        let v = tangential_offset_tables(&self.material, &g, delta_q, &COMPONENTS);
        let spectra = [
            self.conv
                .kernel_spectrum(&circulant_from_centred(&g, &v[0])),
            self.conv
                .kernel_spectrum(&circulant_from_centred(&g, &v[1])),
            self.conv
                .kernel_spectrum(&circulant_from_centred(&g, &v[2])),
        ];
        self.shifted = Some((delta_q, spectra));
        if self.coupling.is_some() {
            let c = tangential_offset_tables(
                &self.material,
                &g,
                delta_q,
                &[Component::Xn, Component::Yn],
            );
            let spectra = [
                self.conv
                    .kernel_spectrum(&circulant_from_centred(&g, &c[0])),
                self.conv
                    .kernel_spectrum(&circulant_from_centred(&g, &c[1])),
            ];
            self.coupling_shifted = Some((delta_q, spectra));
        }
    }

    /// The tangential displacement from the pressure, A_tn p_n (minus its shifted value of the
    /// previous step in rolling), into `cnx`, `cny` (K ≠ 0).
    pub(super) fn prepare_coupling(&mut self, kind: Coupling) {
        self.cnx.fill(0.0);
        self.cny.fill(0.0);
        let Some(direct) = &self.coupling else {
            return;
        };
        let main = match kind {
            Coupling::Direct | Coupling::Shifted => direct,
            Coupling::Steady => self.coupling_steady.as_ref().expect("built"),
        };
        self.conv.apply(&main[0], &self.pn, &mut self.cnx);
        self.conv.apply(&main[1], &self.pn, &mut self.cny);
        if kind == Coupling::Shifted {
            let [sx, sy] = &self.coupling_shifted.as_ref().expect("built").1;
            let prev = self.pn_previous.as_deref().unwrap_or(&self.pn);
            self.conv.apply(sx, prev, &mut self.tmp);
            sub(&mut self.cnx, &self.tmp);
            self.conv.apply(sy, prev, &mut self.tmp);
            sub(&mut self.cny, &self.tmp);
            self.pn_previous = None;
        }
    }
}

/// S += C e_J Δ for a traction change Δ = (`ddx`, `ddy`) at element J = (`jx`, `jy`),
/// over the observation box [ix0, ix1] × [iy0, iy1] (contiguous kernel rows, no allocation).
#[allow(clippy::too_many_arguments)]
pub(super) fn add_column(
    k: &KernelSet,
    g: &Grid,
    jx: usize,
    jy: usize,
    ddx: f64,
    ddy: f64,
    sx: &mut [f64],
    sy: &mut [f64],
    ix0: usize,
    ix1: usize,
    iy0: usize,
    iy1: usize,
) {
    let (nx, ny) = (g.nx, g.ny);
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

pub(super) fn add(a: &mut [f64], b: &[f64]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += y;
    }
}

pub(super) fn sub(a: &mut [f64], b: &[f64]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x -= y;
    }
}
