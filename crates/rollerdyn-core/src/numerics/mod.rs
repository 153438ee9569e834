//! Small numerical building blocks shared by the models: Gauss–Legendre quadrature,
//! bracketed root finding, complete elliptic integrals and least-squares fitting.

pub mod elliptic;
pub mod fit;
pub mod quadrature;
pub mod roots;
pub mod smooth;
