//! Small numerical building blocks shared by the models: Gauss–Legendre quadrature,
//! bracketed root finding, complete elliptic integrals, least-squares fitting and
//! interpolation.

pub mod elliptic;
pub mod fit;
pub mod interpolation;
pub mod quadrature;
pub mod roots;
pub mod smooth;
