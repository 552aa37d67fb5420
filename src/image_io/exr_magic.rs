//! Telling an EXR file from any other by its first four bytes (the OpenEXR magic number), so
//! that a reader of part files or sweep references says "not an EXR file" instead of the
//! `exr` crate's "file identifier missing" or a guess that the file is truncated.

use std::io::Read;
use std::path::Path;

/// The first four bytes of every OpenEXR file.
pub const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// Whether `bytes` can be an EXR file: they start with the magic number, or are a shorter
/// start of it (an EXR file cut off early, which its reader calls truncated).
pub fn could_be_exr(bytes: &[u8]) -> bool {
    let n = bytes.len().min(MAGIC.len());
    bytes[..n] == MAGIC[..n]
}

/// [`could_be_exr`] for the file at `path`, reading only its first bytes.
pub fn file_could_be_exr(path: &Path) -> std::io::Result<bool> {
    let mut start = Vec::with_capacity(MAGIC.len());
    std::fs::File::open(path)?
        .take(MAGIC.len() as u64)
        .read_to_end(&mut start)?;
    Ok(could_be_exr(&start))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exr_files_and_their_starts_pass_others_do_not() {
        assert!(could_be_exr(&[0x76, 0x2f, 0x31, 0x01, 2, 0, 0, 0]));
        assert!(could_be_exr(&[0x76, 0x2f]));
        assert!(could_be_exr(&[]));
        assert!(!could_be_exr(b"\x89PNG\r\n\x1a\n"));
        assert!(!could_be_exr(b"Scene("));
    }
}
