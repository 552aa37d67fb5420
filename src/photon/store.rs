//! Where a photon pass keeps its maps between runs, and whether a kept file can be reused:
//! the scene's `photon_map` file or, when the command line names one, a cache directory
//! keyed by the content hash (`--photon-cache DIR`: `DIR/<hash>.pmap`, which farm parts and
//! sweeps share). A file is reused only when it reads cleanly and its hash is the pass's;
//! anything else is traced again (a corrupt file with a warning) and rewritten.

use std::path::{Path, PathBuf};

use super::file::{decode, PhotonFileError, StoredMaps};
use crate::settings::RenderSettings;

/// Largest photon map file read (bytes): 16 GiB, far above any map that fits in memory.
pub const MAX_FILE_BYTES: u64 = 16 << 30;

/// Where this pass's maps are kept.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file.
    pub path: PathBuf,
    /// Trace and rewrite even when the file matches (`photon_map: (rebuild: true)`).
    pub rebuild: bool,
}

/// The location for a pass with content hash `key`: `--photon-cache DIR` wins over the
/// scene's `photon_map` file (the command line overrides the scene); `None` keeps the maps
/// in memory only.
pub fn location(settings: &RenderSettings, cache: Option<&Path>, key: u64) -> Option<Location> {
    if let Some(dir) = cache {
        return Some(Location {
            path: cache_file(dir, key),
            rebuild: false,
        });
    }
    settings.photon_map.as_ref().map(|f| Location {
        path: f.path.clone(),
        rebuild: f.rebuild,
    })
}

/// The file of hash `key` in cache directory `dir`.
pub fn cache_file(dir: &Path, key: u64) -> PathBuf {
    dir.join(format!("{key:016x}.pmap"))
}

/// Why a kept file is not reused.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Miss {
    /// `rebuild: true`.
    Rebuild,
    /// There is no file yet.
    Absent,
    /// The file was traced for other inputs (its hash).
    Stale(u64),
    /// The file cannot be read or is not a valid photon map (the message, for a warning).
    Unreadable(String),
}

impl std::fmt::Display for Miss {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Rebuild => write!(f, "rebuild requested"),
            Self::Absent => write!(f, "no photon map file yet"),
            Self::Stale(k) => write!(f, "the file was traced for other inputs (hash {k:016x})"),
            Self::Unreadable(why) => write!(f, "{why}"),
        }
    }
}

/// The maps kept at `at`, if they were traced for `key`.
pub fn load(at: &Location, key: u64) -> Result<StoredMaps, Miss> {
    if at.rebuild {
        return Err(Miss::Rebuild);
    }
    let path = &at.path;
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(Miss::Absent),
        Err(e) => return Err(unreadable(&e.to_string())),
    };
    if !meta.is_file() {
        return Err(unreadable("not a regular file"));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(unreadable(&format!(
            "{} bytes is more than the {MAX_FILE_BYTES}-byte limit",
            meta.len()
        )));
    }
    let bytes = std::fs::read(path).map_err(|e| unreadable(&e.to_string()))?;
    match super::file::peek_key(&bytes) {
        Some(k) if k != key => return Err(Miss::Stale(k)),
        _ => {}
    }
    decode(&bytes).map_err(|e: PhotonFileError| unreadable(&e.to_string()))
}

/// The warning about a kept file that cannot be read (printed after the file's path).
fn unreadable(why: &str) -> Miss {
    Miss::Unreadable(format!(
        "cannot reuse this photon map file: {why}; tracing the photons again and rewriting it"
    ))
}
