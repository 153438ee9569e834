//! Shapes of the bodies: the roller (a cylinder with torus edges and spherical end
//! faces) and its derived mass properties.

pub mod circle;
pub mod circle_fast;
pub mod end_flange;
pub mod primitives;
pub mod roller;
