//! Scenarios of dyncontact: the physics crates (half-space contact, integrators, beam)
//! combined into simulations. No I/O: the CLI reads scenario files and writes results.
//!
//! * [`ball_drop`]: a rigid or elastic ball dropped on an elastic half-space,
//!   m z'' = F_n(δ) − m g (docs/ball_drop.md);
//! * [`vehicle_bridge`]: wheels (moving force, moving mass, quarter car, several axles) over a
//!   modal Euler–Bernoulli bridge with Hertz or boundary-element contact, coupled every time
//!   step (Picard, quasi-Newton/Sherman–Morrison (references.md §D4.4), Woodbury, Newton);
//! * [`contact_case`]: a contact case solved (normal, tangential) with its summary;
//! * [`creep_curve`]: creep force against creepage (exact, FASTSIM, linear theory);
//! * [`modes`]: the modal table and mode shapes of a bridge;
//! * [`config`]: scenario files (TOML text) parsed once into these types, with the
//!   numerical defaults and the range checks of every key.

pub mod ball_drop;
pub mod ball_drop_summary;
pub mod config;
pub mod contact_case;
pub mod creep_curve;
pub mod modes;
pub mod moving_load_summary;
pub mod profile_sweep;
pub mod sweep;
pub mod train;
pub mod train_response;
pub mod vehicle_bridge;
pub mod vehicle_bridge_series;
pub mod wheel_rail_case;
