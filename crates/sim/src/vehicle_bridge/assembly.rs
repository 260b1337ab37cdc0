//! The model: DOF layout, mass/damping/stiffness assembly of the contact-free structure,
//! the contact laws and the static-equilibrium start (module documentation, "Start").

use beam::Derivative;
use faer::{Mat, MatRef};
use std::ops::Range;

use integrate::structural::sparse::{
    SparseMatrix, rows_outside, sparse_from_dense, sparse_mul, sparse_mul_add_rows,
};
use integrate::structural::{StepEquation, StructuralMethod, StructuralStepper, StructuralSystem};

use halfspace::law::{ContactModel as LawModel, LawOutput};

use super::contact::{columns, wheel_contact, wheel_error};
use super::linalg::{BlockDiagonal, CapacitanceWork, DenseWork};
use super::{
    Integrator, Scenario, Simulation, SolverStats, VehicleBridgeError, WheelSample, Work, scenario,
};

/// The contact-free linear structure (bridge modes and vehicle), for the stepper.
pub(super) struct Structure {
    pub(super) mass: Mat<f64>,
    pub(super) damping: Mat<f64>,
    pub(super) stiffness: Mat<f64>,
    /// Compressed-row copies of M, C and K (the products of a step in O(nnz): the modal
    /// blocks are diagonal and each vehicle's block is small).
    pub(super) mass_sparse: SparseMatrix,
    pub(super) damping_sparse: SparseMatrix,
    pub(super) stiffness_sparse: SparseMatrix,
    pub(super) gravity_load: Vec<f64>,
    /// Contact load added to the external force (used for the consistent start acceleration).
    pub(super) contact_load: Vec<f64>,
    /// Rows of K q left as they are by `internal_force` (sorted, disjoint): the rows of DOFs
    /// frozen at rest whose K row reaches frozen DOFs only, so their product is unchanged
    /// ([`Structure::keep_rows`]).
    kept_rows: Vec<Range<usize>>,
}

impl Structure {
    /// Keeps the rows of `frozen` (sorted, disjoint ranges of DOFs frozen at rest: their q
    /// does not change) out of later `internal_force` products where the row of K reaches only
    /// frozen DOFs: (K q)_i then depends on unchanged q only, so the value of the last product
    /// is exact. Replaces the previous set; an empty `frozen` computes every row again.
    pub(super) fn keep_rows(&mut self, frozen: &[Range<usize>]) {
        self.kept_rows.clear();
        let k = self.stiffness_sparse.as_ref();
        let symbolic = k.symbolic();
        let (row_ptr, col_idx) = (symbolic.row_ptr(), symbolic.col_idx());
        let is_frozen = |j: usize| frozen.iter().any(|r| r.contains(&j));
        for i in frozen.iter().flat_map(|r| r.clone()) {
            if col_idx[row_ptr[i]..row_ptr[i + 1]]
                .iter()
                .all(|&j| is_frozen(j))
            {
                match self.kept_rows.last_mut() {
                    Some(last) if last.end == i => last.end = i + 1,
                    _ => self.kept_rows.push(i..i + 1),
                }
            }
        }
    }
}

impl StructuralSystem for Structure {
    fn dimension(&self) -> usize {
        self.gravity_load.len()
    }
    fn mass_matrix(&self) -> MatRef<'_, f64> {
        self.mass.as_ref()
    }
    fn damping_matrix(&self) -> Option<MatRef<'_, f64>> {
        Some(self.damping.as_ref())
    }
    fn internal_force(&mut self, q: &[f64], f_int: &mut [f64]) {
        if self.kept_rows.is_empty() {
            sparse_mul(self.stiffness_sparse.as_ref(), q, f_int);
            return;
        }
        // The same operations per row as `sparse_mul` (0 + 1·(K q)_i), the kept rows untouched.
        let n = f_int.len();
        let rows = || rows_outside(n, &self.kept_rows);
        for range in rows() {
            f_int[range].fill(0.0);
        }
        let k = self.stiffness_sparse.as_ref();
        sparse_mul_add_rows(k, 1.0, q, f_int, rows());
    }
    fn tangent_stiffness(&mut self, _q: &[f64], mut k: faer::MatMut<'_, f64>) -> bool {
        k.copy_from(self.stiffness.as_ref());
        true
    }
    fn is_linear(&self) -> bool {
        true
    }
    fn external_force(&mut self, _t: f64, f_ext: &mut [f64]) {
        for ((f, g), c) in f_ext
            .iter_mut()
            .zip(&self.gravity_load)
            .zip(&self.contact_load)
        {
            *f = g + c;
        }
    }
}

/// The static body and bogie displacements of a vehicle with its wheels at their start
/// positions: K_ff q_f = g_f − K_fw z_w (own DOFs; faer's partial-pivoting LU, `DenseLu`).
pub(super) fn static_vehicle(
    v: &super::vehicles::VehicleDofs,
    stiffness: &Mat<f64>,
    gravity_load: &[f64],
    q: &mut [f64],
) -> Result<(), VehicleBridgeError> {
    let own = v.own();
    let f = own.len();
    let wheels = &v.dofs[f..];
    let kff = Mat::<f64>::from_fn(f, f, |r, c| stiffness[(own[r], own[c])]);
    let mut rhs: Vec<f64> = own
        .iter()
        .map(|&i| {
            gravity_load[i]
                - wheels
                    .iter()
                    .map(|&w| stiffness[(i, w)] * q[w])
                    .sum::<f64>()
        })
        .collect();
    let mut lu = integrate::DenseLu::new(f);
    let held = lu.factorize(kff.as_ref(), 0.0).is_ok() && {
        lu.solve_in_place(&mut rhs);
        rhs.iter().all(|x| x.is_finite())
    };
    if !held {
        return Err(super::error::invalid(
            "train.vehicles",
            v.first_wheel as f64,
            "a multibody vehicle's suspension must hold its bodies and bogies (positive stiffnesses)",
        ));
    }
    for (r, &i) in own.iter().enumerate() {
        q[i] = rhs[r];
    }
    Ok(())
}

impl Simulation {
    /// Validates the scenario and sets up the static start (module documentation).
    pub fn new(scenario: Scenario) -> Result<Self, VehicleBridgeError> {
        Self::with_vehicles(scenario, Vec::new())
    }

    /// [`Simulation::new`] with bogie vehicles on some of the wheels (module
    /// [`vehicles`](super::vehicles)): each layout's four wheels (bare wheelsets: no body,
    /// their `static_load` the suspended share of the vehicle's weight) get the vehicle's
    /// body and bogies.
    pub fn with_vehicles(
        mut scenario: Scenario,
        layouts: Vec<super::VehicleLayout>,
    ) -> Result<Self, VehicleBridgeError> {
        let m = scenario.bridge.n_modes();
        let length = scenario.bridge.length();
        scenario::validate(&mut scenario)?;
        let nw0 = scenario.wheels.len();
        let mut wheel_vehicle: Vec<Option<usize>> = vec![None; nw0];
        for (v, layout) in layouts.iter().enumerate() {
            let k0 = layout.first_wheel;
            let count = layout.vehicle.wheelsets();
            if k0 + count > nw0 {
                return Err(super::error::invalid(
                    "train.vehicles",
                    k0 as f64,
                    "a multibody vehicle needs one wheel of the scenario per wheelset",
                ));
            }
            for k in k0..k0 + count {
                let w = &scenario.wheels[k];
                if wheel_vehicle[k].is_some() || w.body_mass != 0.0 || w.wheel_mass <= 0.0 {
                    return Err(super::error::invalid(
                        "train.vehicles",
                        k as f64,
                        "the wheels of a multibody vehicle are its own bare wheelsets (wheel_mass > 0, no body)",
                    ));
                }
                wheel_vehicle[k] = Some(v);
            }
        }
        // DOF layout and matrices.
        let mut n = m;
        let mut wheel_dof = Vec::new();
        let mut body_dof = Vec::new();
        for w in &scenario.wheels {
            wheel_dof.push(n);
            n += 1;
            if w.body_mass > 0.0 {
                body_dof.push(Some(n));
                n += 1;
            } else {
                body_dof.push(None);
            }
        }
        // Body and bogies of each multibody vehicle (module `vehicles`).
        let mut vehicles = Vec::with_capacity(layouts.len());
        for layout in &layouts {
            let matrices = layout.vehicle.matrices();
            let own = matrices.own_dofs;
            let mut dofs: Vec<usize> = (n..n + own).collect();
            n += own;
            dofs.extend((0..matrices.wheelsets()).map(|j| wheel_dof[layout.first_wheel + j]));
            vehicles.push(super::vehicles::VehicleDofs {
                first_wheel: layout.first_wheel,
                bodies: layout.vehicle.bodies(),
                dofs,
                matrices,
            });
        }
        let omegas = scenario.bridge.circular_frequencies().to_vec();
        let modal_c = scenario.damping.velocity_coefficients(&omegas)?;
        let mut mass = Mat::<f64>::zeros(n, n);
        let mut damping = Mat::<f64>::zeros(n, n);
        let mut stiffness = Mat::<f64>::zeros(n, n);
        let mut gravity_load = vec![0.0; n];
        for j in 0..m {
            let mj = scenario.bridge.modal_mass(j)?;
            mass[(j, j)] = mj;
            damping[(j, j)] = mj * modal_c[j];
            stiffness[(j, j)] = mj * omegas[j] * omegas[j];
        }
        let g = scenario.gravity;
        let mut static_loads = Vec::new();
        for (k, w) in scenario.wheels.iter().enumerate() {
            let iw = wheel_dof[k];
            mass[(iw, iw)] = w.wheel_mass;
            // A vehicle's wheelset carries its share of the body and bogies through the
            // suspension (their weights are loads on their own DOFs), not as a force.
            gravity_load[iw] = w.wheel_mass * g
                + if wheel_vehicle[k].is_some() {
                    0.0
                } else {
                    w.static_load
                };
            if let Some(ib) = body_dof[k] {
                mass[(ib, ib)] = w.body_mass;
                gravity_load[ib] = w.body_mass * g;
                for (mat, v) in [
                    (&mut damping, w.suspension_damping),
                    (&mut stiffness, w.suspension_stiffness),
                ] {
                    mat[(iw, iw)] += v;
                    mat[(ib, ib)] += v;
                    mat[(iw, ib)] -= v;
                    mat[(ib, iw)] -= v;
                }
            }
            static_loads.push((w.wheel_mass + w.body_mass) * g + w.static_load);
        }
        for v in &vehicles {
            let vm = &v.matrices;
            for (r, &i) in v.dofs.iter().enumerate() {
                for (c, &j) in v.dofs.iter().enumerate() {
                    stiffness[(i, j)] += vm.stiffness[(r, c)];
                    damping[(i, j)] += vm.damping[(r, c)];
                }
            }
            // Own DOFs: (z, θ) of each body and bogie (weights on the z DOFs).
            for (r, &i) in v.own().iter().enumerate() {
                mass[(i, i)] = vm.mass[r];
                gravity_load[i] = if r % 2 == 0 { vm.mass[r] * g } else { 0.0 };
            }
        }
        let force_scale = static_loads.iter().copied().fold(0.0, f64::max);

        // Contact laws.
        let mut contacts = Vec::with_capacity(static_loads.len());
        let mut contact_tables = super::contact::ContactTables::default();
        for &load in &static_loads {
            contacts.push(wheel_contact(
                &scenario.contact,
                &scenario.geometry,
                load,
                &mut contact_tables,
            )?);
        }

        // Static start.
        let mut q0 = vec![0.0; n];
        let mut forces = Vec::new();
        let mut contact_load = vec![0.0; n];
        for (k, w) in scenario.wheels.iter().enumerate() {
            let delta = match &mut contacts[k] {
                LawModel::Law(law) => law
                    .static_approach(static_loads[k])
                    .map_err(wheel_error(k))?,
                LawModel::Rigid(_) => 0.0,
            };
            let zw = delta - scenario.irregularity.height(w.position);
            q0[wheel_dof[k]] = zw;
            if let Some(ib) = body_dof[k] {
                q0[ib] = zw + w.body_mass * g / w.suspension_stiffness;
            }
            forces.push(static_loads[k]);
            contact_load[wheel_dof[k]] = -static_loads[k];
            if (0.0..=length).contains(&w.position) {
                for j in 0..m {
                    contact_load[j] += static_loads[k] * scenario.bridge.shape(j, w.position)?;
                }
            }
        }
        // The moving forces on the span at t = 0 (module `moving_forces`).
        super::moving_forces::add_modal_load(
            &scenario.moving_forces,
            scenario.speed,
            0.0,
            &*scenario.bridge,
            None,
            1.0,
            &mut vec![0.0; m],
            &mut contact_load[..m],
        )?;
        for v in &vehicles {
            static_vehicle(v, &stiffness, &gravity_load, &mut q0)?;
        }
        let mut structure = Structure {
            mass_sparse: sparse_from_dense(mass.as_ref()),
            damping_sparse: sparse_from_dense(damping.as_ref()),
            stiffness_sparse: sparse_from_dense(stiffness.as_ref()),
            kept_rows: Vec::new(),
            mass,
            damping,
            stiffness,
            gravity_load,
            contact_load: contact_load.clone(),
        };
        // The wheel and body start moving with the rail under them: ż = −c r'(x_k0) keeps
        // δ̇ = ż_w + c r' = 0 (r' by a central difference, h = 1e-6 m).
        let mut v0 = vec![0.0; n];
        for (k, w) in scenario.wheels.iter().enumerate() {
            let h = 1e-6;
            let irr = &scenario.irregularity;
            let slope = (irr.height(w.position + h) - irr.height(w.position - h)) / (2.0 * h);
            v0[wheel_dof[k]] = -scenario.speed * slope;
            if let Some(ib) = body_dof[k] {
                v0[ib] = -scenario.speed * slope;
            }
        }
        // A massless wheel's row and column of M are zero: the stepper treats it as a massless
        // DOF (no inertia in its step row, start acceleration 0; the static start balances the
        // wheel row exactly, so (f_ext − C v − K q)_w = 0 there as well).
        // With Radau5 the structural stepper only holds the reported state (restarted after
        // every output step; module `radau`), so any implicit method serves.
        let method = match scenario.integrator {
            Integrator::Structural(method) => method,
            Integrator::Radau5(_) => StructuralMethod::average_acceleration(),
        };
        let stepper = StructuralStepper::new(method, &mut structure, 0.0, &q0, &v0)?;
        let nw = scenario.wheels.len();
        let ncols: Vec<usize> = contacts.iter().map(|c| columns(c).len()).collect();
        let work = Work {
            x: vec![0.0; n],
            r: vec![0.0; n],
            res: vec![0.0; n],
            f_ext: vec![0.0; n],
            shape_at_wheel: vec![vec![0.0; m]; nw],
            shape_at_columns: ncols.iter().map(|&c| vec![0.0; c * m]).collect(),
            r_at_wheel: vec![0.0; nw],
            r_at_columns: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            column_gap: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            column_force: ncols.iter().map(|&c| vec![0.0; c]).collect(),
            modal_load: vec![vec![0.0; m]; nw],
            g_hat: vec![vec![0.0; n]; nw],
            v: vec![vec![0.0; n]; nw],
            pattern: wheel_dof
                .iter()
                .map(|&iw| (0..m).chain([iw]).collect())
                .collect(),
            span_modes: vec![m; nw],
            moving_load: vec![0.0; m],
            force_shapes: vec![0.0; m],
            g_act: vec![vec![0.0; n]; nw],
            v_act: vec![vec![0.0; n]; nw],
            outputs: vec![LawOutput::default(); nw],
            delta: vec![0.0; nw],
            prev_force: vec![0.0; nw],
            predicted: vec![(0.0, 0); nw],
            last_df: vec![0.0; nw],
            active: Vec::with_capacity(nw),
            compliance: vec![0.0; nw],
            delta_tilde: vec![0.0; nw],
            df: vec![0.0; nw],
            cap: {
                let mut cap = CapacitanceWork::new(n, nw);
                if scenario.coupling.solver == super::CouplingSolver::QuasiNewton {
                    cap.set_fold_tolerance(super::coupling::FOLD_TOLERANCE);
                }
                cap
            },
            dense: DenseWork::default(),
            floor_residual: vec![0.0; n],
            floor_ax: vec![0.0; n],
            floor_ainv_g: vec![0.0; n],
            wheel_floor: vec![0.0; nw],
            force_floor: 0.0,
            floor_bound: false,
            floor_bounded: 0,
            law: super::law_residual::LawResidual {
                force: vec![0.0; nw],
                ..Default::default()
            },
        };
        let mut output_shapes = vec![0.0; m];
        scenario
            .bridge
            .eval_all(scenario.output_point, Derivative::Shape, &mut output_shapes)?;
        let quasi_static_weights = Self::quasi_static_weights(&*scenario.bridge, &output_shapes)?;
        let any_rigid = contacts.iter().any(super::contact::is_rigid);
        let rigid = super::rigid::RigidWork::new(any_rigid, nw, m, n);
        let mut sim = Self {
            contacts,
            contact_tables,
            structure,
            stepper,
            eq: StepEquation::default(),
            wheel_dof,
            body_dof,
            vehicles,
            wheel_vehicle,
            static_loads,
            force_scale,
            contact_load,
            forces,
            samples: vec![WheelSample::default(); nw],
            work,
            a_matrix: BlockDiagonal::new(n),
            a_coefficients: (f64::NAN, f64::NAN, f64::NAN),
            stats: SolverStats::default(),
            output_shapes,
            quasi_static_weights,
            loss_events: 0,
            wheel_loss_events: vec![0; nw],
            static_contact_stiffness: vec![0.0; nw],
            in_contact: vec![true; nw],
            scenario,
            traction: None,
            radau: None,
            rigid,
            sine: None,
            track: None,
            resting: Default::default(),
            points: Default::default(),
        };
        sim.sine = beam::sine_amplitudes(&*sim.scenario.bridge)?;
        sim.hold_resting_vehicles(true);
        sim.solve_detached_vehicles(true);
        sim.initial_samples()?;
        sim.rigid_start()?;
        if let Integrator::Radau5(spec) = sim.scenario.integrator {
            sim.start_radau5(spec)?;
        }
        Ok(sim)
    }

    /// Fills the samples at t = 0 (static state).
    fn initial_samples(&mut self) -> Result<(), VehicleBridgeError> {
        self.wheel_geometry(self.stepper.t())?;
        for k in 0..self.scenario.wheels.len() {
            let x = self.scenario.wheels[k].position;
            let q = self.stepper.q().to_vec();
            let zw = q[self.wheel_dof[k]];
            let delta = self.work.approach(k, self.wheel_dof[k], &q);
            let mut out = match &mut self.contacts[k] {
                LawModel::Rigid(_) => LawOutput {
                    force: self.static_loads[k],
                    ..LawOutput::default()
                },
                LawModel::Law(law) => {
                    let ncol = law.columns().len();
                    let zero = vec![0.0; ncol];
                    let mut cf = vec![0.0; ncol];
                    law.evaluate(delta, &zero, &mut cf, true)
                        .map_err(wheel_error(k))?
                }
            };
            out.iterations = 0;
            self.static_contact_stiffness[k] = out.stiffness;
            self.samples[k] = WheelSample {
                position: x,
                wheel_displacement: zw,
                body_displacement: self.wheel_vehicle[k]
                    .map(|v| self.vehicles[v].body_over(k - self.vehicles[v].first_wheel))
                    .or(self.body_dof[k])
                    .map_or(zw, |ib| q[ib]),
                body_acceleration: 0.0,
                wheel_acceleration: 0.0,
                approach: delta,
                contact: out,
            };
        }
        Ok(())
    }
}
