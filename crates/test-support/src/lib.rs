//! What the workspace's tests share, once (dev-only: a `dev-dependency` of the crates whose
//! tests use it, never a dependency of a library, never published):
//!
//! - [`Scratch`], a fresh directory under the system temp directory, removed on drop;
//! - [`scenarios`], the fixture scenarios (`fixtures/scenarios/`) and edits of them;
//! - [`MemoryFiles`], files held in memory as a study's [`pipeline::DataSource`];
//! - [`hostile`], hostile files (a FIFO, a sparse file) and a watchdog ([`hostile::within`])
//!   for tests of what must not block.
//!
//! It implements none of the paper's equations: it only sets up what tests compute on.

pub mod hostile;
mod memory;
pub mod scenarios;
mod scratch;

pub use memory::MemoryFiles;
pub use scratch::Scratch;
