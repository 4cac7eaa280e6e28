//! The joint fit over several mountings (issue 29): eq. 18 and eq. 23 as its special cases on
//! the fixtures' data, the separability analysis, and the coverage of simulated campaigns.

mod coverage;
mod numpy_data;
mod separable;
mod special_cases;
mod type_b_coverage;
