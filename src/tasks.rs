//! What a run is asked to do (render, bake or both): a run input that the frame and the
//! memory-budget estimates both read, kept in a leaf module so neither imports the other.

/// What the user asked this run to do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Tasks {
    /// Render the render camera (`stagelight render`).
    pub render: bool,
    /// Bake the scene's bake requests (`stagelight bake`, or `render --bake`).
    pub bake: bool,
}

impl Default for Tasks {
    fn default() -> Self {
        Self {
            render: true,
            bake: false,
        }
    }
}
