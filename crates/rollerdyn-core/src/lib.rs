//! # rollerdyn-core
//!
//! Physics and numerics of rollerdyn, a dynamic simulation of full-complement
//! (cageless) cylindrical roller bearings after Wolf & Fatemi, *Dynamic Simulation of
//! Full Complement Cylindrical Roller Bearings with a Semi-Analytical Roller End-Flange
//! Contact Detection Method* (the "reference paper"; equation numbers in doc comments
//! refer to it unless another source is named).
//!
//! Everything inside is SI: metres, newtons, pascals, seconds, kelvin, radians.
//!
//! * [`tribology`]: contact mechanics (Hertz, Tripp), lubricant rheology, film
//!   thickness, traction, boundary and mixed friction, rolling resistance.
//! * [`geometry`]: roller and flange shapes, the basic figures (sphere, cone, torus).
//! * [`contact`]: roller end–flange contact detection.
//! * [`numerics`]: quadrature, root finding, complete elliptic integrals, fitting.

pub mod bearing;
pub mod contact;
pub mod dynamics;
pub mod error;
pub mod geometry;
pub mod numerics;
pub mod tribology;

pub use error::{Error, Result};
