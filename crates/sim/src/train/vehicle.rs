//! The rail vehicle models of a train (2-D vertical plane, SI units): the parameters only.
//! The equations of motion of each model live in the simulation that uses it
//! (`vehicle_bridge`); the scenario-file keys are the field names (docs/trains.md).

/// One vehicle of a train, in running order. Positions inside a vehicle are distances
/// *behind* its leading axle \[m\] (≥ 0).
#[derive(Debug, Clone, PartialEq)]
pub enum VehicleSpec {
    /// `moving_forces`: axle loads only, no inertia.
    MovingForces(MovingForces),
    /// `quarter_car`: one axle, a wheel mass under a sprung body mass.
    QuarterCar(QuarterCar),
    /// `sprung_mass`: one axle, a body mass on a spring–damper on a massless wheel.
    SprungMass(SprungMass),
    /// `bogie_vehicle`: car body on two bogies on four wheelsets (10 DOFs).
    BogieVehicle(BogieVehicle),
    /// `articulated`: car bodies sharing their bogies with their neighbours.
    Articulated(Articulated),
}

impl VehicleSpec {
    /// The scenario-file `type` name.
    pub fn type_name(&self) -> &'static str {
        match self {
            Self::MovingForces(_) => "moving_forces",
            Self::QuarterCar(_) => "quarter_car",
            Self::SprungMass(_) => "sprung_mass",
            Self::BogieVehicle(_) => "bogie_vehicle",
            Self::Articulated(_) => "articulated",
        }
    }
}

/// `moving_forces`: constant axle loads travelling with the train.
#[derive(Debug, Clone, PartialEq)]
pub struct MovingForces {
    /// From this vehicle's leading axle to the next vehicle's leading axle \[m\].
    pub length: f64,
    /// Axle positions behind the leading axle \[m\] (first 0, non-decreasing).
    pub axle_positions: Vec<f64>,
    /// Axle loads \[N\] (downwards positive), one per axle position.
    pub axle_loads: Vec<f64>,
}

/// `quarter_car`: wheel (unsprung) mass, suspension, body (sprung) mass; one axle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct QuarterCar {
    /// From this vehicle's axle to the next vehicle's leading axle \[m\].
    pub length: f64,
    /// Wheel mass \[kg\].
    pub wheel_mass: f64,
    /// Body mass \[kg\].
    pub body_mass: f64,
    /// Suspension stiffness \[N/m\].
    pub suspension_stiffness: f64,
    /// Suspension damping \[N s/m\].
    pub suspension_damping: f64,
}

/// `sprung_mass`: a body on a spring–damper on a massless wheel; one axle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SprungMass {
    /// From this vehicle's axle to the next vehicle's leading axle \[m\].
    pub length: f64,
    /// Body mass \[kg\].
    pub body_mass: f64,
    /// Suspension stiffness \[N/m\].
    pub suspension_stiffness: f64,
    /// Suspension damping \[N s/m\].
    pub suspension_damping: f64,
}

/// `bogie_vehicle`: car body (bounce z, pitch θ) on two bogies (z, θ) at ±`bogie_spacing`/2
/// from the body centre, each on two wheelsets at ±`wheelbase`/2 from the bogie centre;
/// primary suspension per wheelset, secondary per bogie (both rails together). 10 DOFs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BogieVehicle {
    /// From this vehicle's leading axle to the next vehicle's leading axle \[m\]
    /// (≥ `bogie_spacing` + `wheelbase`).
    pub length: f64,
    /// Car body mass \[kg\].
    pub body_mass: f64,
    /// Car body pitch inertia \[kg m²\].
    pub body_pitch_inertia: f64,
    /// Distance between the two bogie centres \[m\].
    pub bogie_spacing: f64,
    /// Bogie mass \[kg\].
    pub bogie_mass: f64,
    /// Bogie pitch inertia \[kg m²\].
    pub bogie_pitch_inertia: f64,
    /// Axle distance within a bogie \[m\].
    pub wheelbase: f64,
    /// Wheelset mass \[kg\].
    pub wheelset_mass: f64,
    /// Primary suspension stiffness per wheelset \[N/m\].
    pub primary_stiffness: f64,
    /// Primary suspension damping per wheelset \[N s/m\].
    pub primary_damping: f64,
    /// Secondary suspension stiffness per bogie \[N/m\].
    pub secondary_stiffness: f64,
    /// Secondary suspension damping per bogie \[N s/m\].
    pub secondary_damping: f64,
}

/// `articulated` as written in a train table: `bodies` identical car bodies in a row (bounce,
/// pitch), body i resting at its two ends on bogie i and bogie i + 1 (`bodies` + 1 identical
/// bogies, the inner ones shared with the neighbour), bogie centres `bogie_spacing` apart, each
/// body's centre of gravity midway between its supports; bogies and wheelsets as in
/// [`BogieVehicle`]. The secondary suspension acts between each body end and its bogie.
/// [`UniformArticulated::build`] gives the general [`Articulated`] vehicle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformArticulated {
    /// From the leading axle to the next vehicle's leading axle \[m\].
    pub length: f64,
    /// Number of car bodies (≥ 1).
    pub bodies: usize,
    /// Car body mass \[kg\] (each).
    pub body_mass: f64,
    /// Car body pitch inertia \[kg m²\] (each).
    pub body_pitch_inertia: f64,
    /// Distance between neighbouring bogie centres (a body's two supports) \[m\].
    pub bogie_spacing: f64,
    /// Bogie mass \[kg\].
    pub bogie_mass: f64,
    /// Bogie pitch inertia \[kg m²\].
    pub bogie_pitch_inertia: f64,
    /// Axle distance within a bogie \[m\].
    pub wheelbase: f64,
    /// Wheelset mass \[kg\].
    pub wheelset_mass: f64,
    /// Primary suspension stiffness per wheelset \[N/m\].
    pub primary_stiffness: f64,
    /// Primary suspension damping per wheelset \[N s/m\].
    pub primary_damping: f64,
    /// Secondary suspension stiffness per body end \[N/m\].
    pub secondary_stiffness: f64,
    /// Secondary suspension damping per body end \[N s/m\].
    pub secondary_damping: f64,
}

impl UniformArticulated {
    /// The articulated vehicle: every body with its centre of gravity midway between its
    /// supports (`bogie_spacing`/2 from each), every bogie alike.
    pub fn build(&self) -> Articulated {
        let half = 0.5 * self.bogie_spacing;
        Articulated {
            length: self.length,
            bodies: vec![
                ArticulatedBody {
                    mass: self.body_mass,
                    pitch_inertia: self.body_pitch_inertia,
                    front: half,
                    rear: half,
                    secondary_stiffness: self.secondary_stiffness,
                    secondary_damping: self.secondary_damping,
                };
                self.bodies
            ],
            bogies: vec![
                ArticulatedBogie {
                    mass: self.bogie_mass,
                    pitch_inertia: self.bogie_pitch_inertia,
                    wheelbase: self.wheelbase,
                    wheelset_mass: self.wheelset_mass,
                    primary_stiffness: self.primary_stiffness,
                    primary_damping: self.primary_damping,
                };
                self.bodies + 1
            ],
        }
    }
}

/// One car body of an [`Articulated`] vehicle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArticulatedBody {
    /// Mass \[kg\].
    pub mass: f64,
    /// Pitch inertia about its centre of gravity \[kg m²\].
    pub pitch_inertia: f64,
    /// From its centre of gravity forward to the centre of the bogie under its front end \[m\].
    pub front: f64,
    /// From its centre of gravity back to the centre of the bogie under its rear end \[m\].
    pub rear: f64,
    /// Secondary suspension stiffness at each end \[N/m\].
    pub secondary_stiffness: f64,
    /// Secondary suspension damping at each end \[N s/m\].
    pub secondary_damping: f64,
}

/// One bogie of an [`Articulated`] vehicle: two wheelsets `wheelbase` apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArticulatedBogie {
    /// Mass \[kg\].
    pub mass: f64,
    /// Pitch inertia \[kg m²\].
    pub pitch_inertia: f64,
    /// Axle distance \[m\].
    pub wheelbase: f64,
    /// Mass of each of its wheelsets \[kg\].
    pub wheelset_mass: f64,
    /// Primary suspension stiffness per wheelset \[N/m\].
    pub primary_stiffness: f64,
    /// Primary suspension damping per wheelset \[N s/m\].
    pub primary_damping: f64,
}

/// `articulated`: n car bodies in a row (bounce, pitch), body j resting with its front end on
/// bogie j and its rear end on bogie j + 1 (n + 1 bogies: the inner ones shared by two
/// neighbouring bodies, Jacobs bogies; the end ones carry one body end, like the conventional
/// bogie under a Eurostar end coach). Bodies and bogies may differ from each other, and a
/// body's centre of gravity need not lie midway between its supports. Bogie j + 1's centre is
/// `bodies[j].front + bodies[j].rear` behind bogie j's; the leading axle is the first of
/// bogie 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Articulated {
    /// From the leading axle to the next vehicle's leading axle \[m\].
    pub length: f64,
    /// The car bodies, leading body first (≥ 1).
    pub bodies: Vec<ArticulatedBody>,
    /// The bogies, leading bogie first (one more than the bodies).
    pub bogies: Vec<ArticulatedBogie>,
}
