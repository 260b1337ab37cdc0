//! Wheel and rail profiles and the rigid wheel–rail contact geometry (references.md §W).
//!
//! - [`profile`]: piecewise profiles z(y) of lines, arcs, polynomials and cubic pieces;
//! - [`s1002`]: the S1002 wheel (EN 13715) from its published sections;
//! - [`rail_60e1`]: the 60E1 rail head (EN 13674-1) from its published drawing dimensions.
//!
//! Units are SI (metres). No file I/O: parsers take text, the CLI reads files.

pub mod error;
pub mod profile;
pub mod rail_60e1;
pub mod s1002;

pub use error::WheelRailError;
pub use profile::{Jump, Profile, Segment};
pub use rail_60e1::rail_60e1;
pub use s1002::s1002;
