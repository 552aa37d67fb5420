//! The stage table: the whole frame order in one place, each stage with its run condition.
//!
//! Stages still to come (contours) take their slots here when they are built:
//!
//! | order | stage             | runs when the scene has                              |
//! |-------|-------------------|------------------------------------------------------|
//! | 1     | `expand_geometry` | procedural geometry components (`Procedural`, `Scatter`) |
//! | 2     | `tessellate`      | parametric surfaces, subdivision meshes, true displacement |
//! | 3     | `build_accel`     | instances with triangles and a consumer of rays       |
//! | 4     | `trace_photons`   | caustics/GI on, a `Direct` render, a light with power |
//! | 5     | `bake_lightmaps`  | bake requests, in a run that bakes                    |
//! | 6     | `shade`           | a render camera                                      |
//! | 7     | `draw_contours`   | contour shaders (not built yet)                       |
//! | 8     | `write_output`    | a shaded image and outputs to write                  |

pub mod bake_lightmaps;
pub mod build_accel;
pub mod expand_geometry;
pub mod shade;
pub mod tessellate;
pub mod trace_photons;
pub mod write_output;

use hecs::World;

use prelude::*;

/// Imports shared by the stage modules.
mod prelude {
    pub use crate::frame::Frame;
    pub use crate::schedule::{Decision, Stage, StageError, Work};
}

/// The ordered stage table.
pub const STAGES: &[Stage] = &[
    Stage {
        name: "expand_geometry",
        condition: expand_geometry::should_run,
        run: expand_geometry::run,
    },
    Stage {
        name: "tessellate",
        condition: tessellate::should_run,
        run: tessellate::run,
    },
    Stage {
        name: "build_accel",
        condition: build_accel::should_run,
        run: build_accel::run,
    },
    Stage {
        name: "trace_photons",
        condition: trace_photons::should_run,
        run: trace_photons::run,
    },
    Stage {
        name: "bake_lightmaps",
        condition: bake_lightmaps::should_run,
        run: bake_lightmaps::run,
    },
    Stage {
        name: "shade",
        condition: shade::should_run,
        run: shade::run,
    },
    Stage {
        name: "write_output",
        condition: write_output::should_run,
        run: write_output::run,
    },
];

/// Runs the whole table over `world`; the report lands in `frame.report`.
pub fn run(world: &mut World, frame: &mut Frame) -> Result<(), StageError> {
    crate::schedule::run_stages(STAGES, world, frame)
}
