//! Equations of motion and time integration.
//!
//! * [`rigid`]: kinematics and Euler's equations of axisymmetric rigid bodies.
//! * [`integrate`]: the stiff adaptive integration driver (knows nothing of bearings).
//! * [`sparse_lu`]: the Newton iterations' linear solver (LU on the non-zeros).
//! * [`team`]: helper threads that share short parallel maps with the calling thread.

pub mod integrate;
pub mod rigid;
pub mod sparse_lu;
pub mod team;
