//! The DCC writer's behaviour: both fixture studies' certificates validate against PTB's
//! schema (offline, xmllint) and read back equal to their results; hostile text stays data.

mod fixtures;
mod hostile;
mod tree;
