//! Wheel and rail profiles and the rigid wheel–rail contact geometry (references.md §W).
//!
//! - [`profile`]: piecewise profiles z(y) of lines, arcs, polynomials and cubic pieces;
//! - [`s1002`](mod@s1002): the S1002 wheel (EN 13715) from its published sections;
//! - [`measured`]: profiles from measured points (text, CSV, SIMPACK/CONTACT point blocks),
//!   smoothing spline;
//! - [`rail_60e1`](mod@rail_60e1): the 60E1 rail head (EN 13674-1) from its published drawing dimensions;
//! - [`placed`]: a profile rotated and translated into the track cross-section;
//! - [`contact_point`]: the rigid contact candidates (local minima of the vertical distance);
//! - [`wheelset`]: gauge, inclination, back-to-back distance, lateral shift and roll; the
//!   contact of both wheels and the rolling radius difference;
//! - [`conicity`]: equivalent conicity from Δr(y);
//! - [`gap`]: the undeformed gap h(x, t) in a candidate's contact plane;
//! - [`patches`]: the candidates grouped into patches and solved with the half-space solver;
//! - [`law`]: one wheel's contact as a force law F(δ) of its vertical approach.
//!
//! Units are SI (metres). No file I/O: parsers take text, the CLI reads files.

pub mod conicity;
pub mod contact_point;
pub mod error;
pub mod gap;
pub mod law;
pub mod measured;
pub mod patches;
pub mod placed;
pub mod profile;
pub mod rail_60e1;
pub mod s1002;
pub mod wheelset;

pub use conicity::equivalent_conicity;
pub use contact_point::ContactCandidate;
pub use error::WheelRailError;
pub use gap::{ContactPlane, Side};
pub use law::ProfileLaw;
pub use measured::{ProfileKind, parse_profile};
pub use patches::{Patch, PatchOptions, WheelLoad, WheelSolution, solve_wheel};
pub use placed::PlacedProfile;
pub use profile::{Jump, Profile, Segment};
pub use rail_60e1::rail_60e1;
pub use s1002::s1002;
pub use wheelset::{Roll, WheelContact, Wheelset, WheelsetContact, WheelsetParams};
