//! An image texture the scene loader decoded: its texels stay in memory for the whole run,
//! so the run's memory estimate counts them (`budget::estimate`), located at the texture's
//! `file`. Spawned with the file's `Name` (as written) and `SourceLink`.

/// The size of one decoded image texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecodedImage {
    /// Texels per row.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// Bytes of its texels and alpha once decoded.
    pub bytes: u64,
}
