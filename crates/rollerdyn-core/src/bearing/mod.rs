//! The dynamic bearing model (paper sect. 3, 4): bodies, state layout, contacts, and the
//! equations of motion; [`run`] drives a whole simulation and records its outputs.
//!
//! [`model`] holds the model and names the stages of a right-hand side, each in a module
//! of its own: [`state`] (kinematics from the state), [`topology`] (the contacts),
//! [`contacts`], [`line_contacts`], [`detection`] and [`flange_contacts`] (each contact's
//! forces, with [`forces`] the laws at one section), [`equations`] (loads per body, rates,
//! energy) and [`jacobian`]; [`profile`] samples their time, [`statics`] finds a
//! quasi-static start.

pub mod contacts;
pub mod detection;
pub mod equations;
pub mod flange_contacts;
pub mod forces;
pub mod jacobian;
pub mod line_contacts;
pub mod model;
pub mod params;
pub mod profile;
pub mod quasi_static;
pub mod roller_train;
pub mod run;
pub mod skew_balance;
pub mod state;
pub mod statics;
pub mod topology;
pub mod workspace;

#[cfg(test)]
mod conservation_tests;
#[cfg(test)]
mod frame_tests;
#[cfg(test)]
mod lubrication_tests;
#[cfg(test)]
pub(crate) mod test_b1;

pub use model::BearingModel;
pub use params::{
    BearingParams, Carrier, Detector, FlangeLaw, History, ModelOptions, RollingResistance,
    SurfacePair,
};
pub use workspace::{BearingSystem, Workspace};
