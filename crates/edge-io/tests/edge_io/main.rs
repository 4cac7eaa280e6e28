//! Behaviour of edge-io's output sets (the capped reader is tested beside its code).

mod output;
