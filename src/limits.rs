//! Hard limits on what a run reads and starts (threads, scene and mesh file sizes) and the
//! size-limited file read: a leaf module, so the scene loader and the guards share it.

/// The most worker threads a run starts. More than this buys nothing on any machine
/// stagelight targets and costs seconds of thread start-up (and megabytes of stacks)
/// before the first pixel; `--threads` above it is refused.
pub const MAX_THREADS: u32 = 1024;

/// The largest scene file (RON, RIB, include) read, in bytes: 64 MiB (meshes of that size
/// belong in OBJ or PLY files).
pub const MAX_SCENE_FILE_BYTES: u64 = 64 << 20;

/// The largest mesh file (OBJ, PLY) read, in bytes: 4 GiB.
pub const MAX_MESH_FILE_BYTES: u64 = 4 << 30;

/// Reads a whole file, refusing one larger than `limit` bytes (or one that never ends, such
/// as `/dev/zero`) after reading at most `limit + 1` bytes. The error's text is the reason
/// printed after the file name.
pub fn read_file(path: &std::path::Path, limit: u64, what: &str) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(std::io::Error::other(format!(
            "larger than {} MiB, the limit for a {what}",
            limit >> 20
        )));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reading_stops_at_the_limit() {
        let err = read_file(std::path::Path::new("/dev/zero"), 1 << 20, "scene file").unwrap_err();
        assert_eq!(
            err.to_string(),
            "larger than 1 MiB, the limit for a scene file"
        );
    }
}
