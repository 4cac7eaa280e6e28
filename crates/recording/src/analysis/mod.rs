//! The analysis of a loaded recording: the harmonic fit of a probe recording with its
//! diagnostics ([`probe`]), the reduction of a raw PIGA recording to its mean output rate
//! ([`piga`]), and the diagnostics' words ([`diagnostic`]). The statistics themselves are
//! `harmonics`'; this module adds what only the file knows (its lines, its format's
//! choices, where its angle came from).

pub(crate) mod diagnostic;
pub(crate) mod piga;
pub(crate) mod probe;
