//! Fitting models to lab records: the optimisers of thesis ch. 3-4.

pub mod nsga2;
