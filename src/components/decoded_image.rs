//! An image the scene loader decoded: an image texture, a displacement image or an
//! environment map. Its texels stay in memory for the whole run, so the run's memory
//! estimate counts them (`budget::estimate`), located at the image's `file`. Spawned with
//! the file's `Name` (as written) and `SourceLink`.

/// What a decoded image is read as, which decides what it holds and how messages name it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageContent {
    /// An image texture of a shader graph: colour texels and alpha.
    Texture,
    /// A displacement image: one height per texel.
    Heights,
    /// A lat-long environment map: radiance texels, and, for the scene's environment (which
    /// is also a light), the importance-sampling tables built from them.
    EnvironmentMap {
        /// Whether the sampling tables are counted (the scene's environment).
        sampled: bool,
    },
}

impl ImageContent {
    /// What needs the memory, for messages: `the texels of a 1024×512 image`.
    pub fn describe(self, width: u32, height: u32) -> String {
        match self {
            Self::Texture => format!("the texels of a {width}×{height} image"),
            Self::Heights => format!("the heights of a {width}×{height} displacement image"),
            Self::EnvironmentMap { sampled: true } => {
                format!("the texels and sampling tables of a {width}×{height} environment map")
            }
            Self::EnvironmentMap { sampled: false } => {
                format!("the texels of a {width}×{height} environment map")
            }
        }
    }
}

/// The size of one decoded image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecodedImage {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Bytes it takes once decoded (for a sampled environment map, at the peak of building
    /// its tables).
    pub bytes: u64,
    /// What it is read as.
    pub content: ImageContent,
}

impl DecodedImage {
    /// What needs the memory, for messages (see [`ImageContent::describe`]).
    pub fn describe(&self) -> String {
        self.content.describe(self.width, self.height)
    }
}
