//! Fitting model parameters to lab records (thesis ch. 3 and 4).

pub mod dual;
pub mod experiment;
pub mod forcing;
pub mod homotopy;
pub mod identifiability;
pub mod input_noise;
pub mod lanes;
pub mod lsq;
pub mod nsga2;
pub mod objectives;
pub mod parametrization;
pub mod phm;
pub mod problem;
pub mod regression;
pub mod run;
pub mod sensitivity;
