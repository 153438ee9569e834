//! Equations of motion and time integration.
//!
//! * [`rigid`]: kinematics and Euler's equations of axisymmetric rigid bodies.
//! * [`integrate`]: the stiff adaptive integration driver (knows nothing of bearings).

pub mod integrate;
pub mod rigid;
