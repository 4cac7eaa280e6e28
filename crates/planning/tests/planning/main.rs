//! Behaviour of the planner: optimality against exhaustive search, the prediction against
//! simulation, and infeasible plans as errors.

mod exhaustive;
mod infeasible;
mod paper;
mod raw;
mod simulation;
mod two_orientation;
