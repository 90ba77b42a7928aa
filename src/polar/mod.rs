//! Polarized light: Stokes vectors and Mueller matrices ([`stokes`]), the Mueller matrices of
//! smooth interfaces ([`fresnel`]), and the two modes of light in a birefringent crystal
//! ([`crystal`]). Pure functions and small value types; the transport that uses them is
//! [`crate::integrator`]'s polarized path tracer.

pub mod crystal;
pub mod fresnel;
pub mod interface;
pub mod modes;
pub mod stokes;

pub use stokes::{Analyzer, Mueller, Stokes};
