//! The dynamic bearing model (paper sect. 3, 4): bodies, state layout, contacts, and the
//! equations of motion; [`run`] drives a whole simulation and records its outputs.

pub mod forces;
pub mod model;
pub mod params;
pub mod run;
pub mod state;
pub mod statics;

pub use model::BearingModel;
pub use params::{BearingParams, Detector, History, SurfacePair};
