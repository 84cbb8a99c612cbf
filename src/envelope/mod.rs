//! The math of `pipearm envelope`: the spread of each uncertain scenario key ([`dist`]), the
//! seeded sample designs that draw from them ([`sample`]: Latin hypercube, Saltelli), and the
//! ranking of the keys by their effect on a result ([`sensitivity`]: Sobol indices, standardized
//! regression coefficients, order-statistic quantiles). Everything here is pure and deterministic:
//! the same seed gives the same numbers on every platform.

pub mod dist;
pub mod sample;
pub mod sensitivity;
