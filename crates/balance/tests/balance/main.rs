//! Behaviour of the balance advisor: closed loops through the simulator, the stiffness model,
//! the paper check and bad input.

mod closed_loop;
mod common;
mod errors;
mod paper;
mod two_plane;
