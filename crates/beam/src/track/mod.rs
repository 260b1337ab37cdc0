//! The railway track between the wheels and the bridge (references.md §D5): an Euler–Bernoulli
//! rail in Hermite finite elements (or a Timoshenko rail in interdependent-interpolation
//! elements, [`RailElement`], §D5.5), continuous over an approach embankment, the bridge and an
//! exit embankment, on discrete supports every sleeper spacing (rail pad, sleeper, ballast,
//! optionally ballast mass and subgrade; or a direct-fastened/slab support), standing on rigid
//! ground off the bridge and on the bridge modes on it.
//!
//! * [`RailSection`]: EI, mass per length, κGA and ρI, presets 60E1, 54E1 (EN 13674-1) and
//!   Zhai's CHN60; [`RailBeam`]: Euler–Bernoulli (default) or Timoshenko;
//! * [`RailElement`]: the rail element's stiffness, consistent mass and shape functions;
//! * [`SpringDamper`], [`SupportStack`]: the support chain at one sleeper, presets for ballasted
//!   high-speed track (Zhai, Wang & Lin 2004) and a slab track;
//! * [`TrackLayout`], [`TrackSupports`], [`Track`]: the model, its sparse symmetric M, C, K, the
//!   Hermite interpolation of the rail displacement ([`RailPoint`]: the same weights give the
//!   consistent load vector of a point force), chain forces, static solution;
//! * [`TrackNewmark`]: Newmark average-acceleration time stepping with the step matrix
//!   factorised once (sparse Cholesky);
//! * [`Receptance`]: the harmonic response (K − ω²M + iωC) u = F.
//!
//! ```
//! use beam::track::{RailSection, SupportStack, Track, TrackLayout, TrackSupports};
//!
//! // 60E1 on the ballasted high-speed chain, 30 m of track on ground, a 100 kN load mid-way.
//! let layout = TrackLayout::new(15.0, 0.0, 15.0, 0.6)?;
//! let supports = TrackSupports::uniform(SupportStack::ballasted_high_speed());
//! let track = Track::on_ground(RailSection::e60(), layout, &supports)?;
//! let mut load = vec![0.0; track.n_dofs()];
//! track.add_point_force(15.3, 100e3, &mut load)?;
//! let u = track.static_solution(&load)?;
//! let w = track.rail_displacement(15.3, &u)?;
//! assert!(w > 1e-3 && w < 3e-3); // about 2 mm over a sleeper
//! # Ok::<(), beam::BeamError>(())
//! ```

mod dynamics;
mod element;
mod model;
mod rail;
mod receptance;
mod sparse;
mod support;

pub use dynamics::TrackNewmark;
pub use element::RailElement;
pub use model::{
    Foundation, MAX_TRACK_NODES, RailPoint, Sleeper, Track, TrackLayout, TrackSupports, Zone,
};
pub use rail::{
    RAIL_SHEAR_COEFFICIENT, RAIL_STEEL_POISSON_RATIO, RAIL_STEEL_YOUNGS_MODULUS,
    ROTARY_INERTIA_RANGE, RailBeam, RailSection, SHEAR_STIFFNESS_RANGE,
};
pub use receptance::Receptance;
pub use sparse::{SparseCholesky, SparseReach};
pub use support::{SpringDamper, SupportStack};
