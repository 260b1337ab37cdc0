//! The normal–tangential coupling term of W for dissimilar materials (K ≠ 0): the
//! pressure's own tangential displacement A_tn p_n (references.md §C3.2), in the form each
//! problem needs.

use super::TangentialSolver;
use crate::operator::{TangentialInfluenceOperator, TangentialKernel, Update};

/// Which coupling term enters W (K ≠ 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Coupling {
    /// A_tn p_n (a shift from the unloaded state).
    Direct,
    /// (A_tn − A_v,tn(δx)) p_n (steady rolling).
    Steady,
    /// A_tn p_n − A_v,tn(δq) p_n' (a transient rolling step over δq).
    Shifted(f64),
}

impl<T: TangentialInfluenceOperator> TangentialSolver<T> {
    /// The tangential displacement from the pressure, A_tn p_n (minus its shifted value of the
    /// previous step in rolling), into `cnx`, `cny` (zero for K = 0). The kernels used must be
    /// prepared.
    pub(super) fn prepare_coupling(&mut self, kind: Coupling) {
        if self.operator.material().k == 0.0 {
            self.cnx.fill(0.0);
            self.cny.fill(0.0);
            return;
        }
        let main = match kind {
            Coupling::Direct | Coupling::Shifted(_) => TangentialKernel::Direct,
            Coupling::Steady => TangentialKernel::Steady,
        };
        self.operator
            .pressure_product(main, Update::Set, &self.pn, (&mut self.cnx, &mut self.cny));
        if let Coupling::Shifted(delta_q) = kind {
            let prev = self.pn_previous.as_deref().unwrap_or(&self.pn);
            self.operator.pressure_product(
                TangentialKernel::Shifted(delta_q),
                Update::Subtract,
                prev,
                (&mut self.cnx, &mut self.cny),
            );
            self.pn_previous = None;
        }
    }
}

pub(super) fn add(a: &mut [f64], b: &[f64]) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += y;
    }
}
