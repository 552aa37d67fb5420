//! The memory budget of a run (issue 18, family 2): the up-front estimates ([`estimate`])
//! that refuse a scene whose stages would need more than the run's budget
//! ([`Budget`], kept in [`crate::memory_budget`]), before anything of that size is allocated.
//! Image textures are counted by the scene loader, from their headers, before they are
//! decoded (`scene::nodes::textures`), and then by their decoded size among the estimates
//! ([`crate::components::DecodedImage`]), so that they add to the run's total.

pub mod estimate;
pub mod worst_case;

pub use crate::memory_budget::{human, parse_bytes, probe, Budget};
