//! Photon map files (mental ray `photonmap file`): the photons of the caustic and global maps
//! in tree order with their split axes, the number of photons emitted for each, and the
//! content hash of everything they depend on ([`super::key`]), so that a run whose hash
//! matches loads the maps instead of tracing them and renders the same bytes.
//!
//! **Layout** (little-endian): the magic line `stagelight photon map\n`, the format version
//! (`u32`, 2), the content hash (`u64`), a `u32` of present maps (bit 0 caustics, bit 1
//! global), then per present map `emitted` (`u64`, over all passes), the number of photon
//! passes `P` (`u32`, ≥ 1: more for a progressive map) and `P` trees, each the photon count
//! `n` (`u64`), `n` photons of 12 `f32` (position, power, incoming, normal) and `n` split
//! axes (`u8`, 0–2); last, the FNV-1a hash of every byte before it (`u64`). A reader checks the magic, the
//! version, the sizes against the file's length before allocating, the checksum, the axes
//! and that every value is finite, so a truncated or corrupt file is an error, never a crash
//! or wrong light.

use glam::Vec3;

use super::kdtree::{Photon, PhotonMap};
use crate::hash::Fnv64;

/// The first bytes of every photon map file.
pub const MAGIC: &[u8] = b"stagelight photon map\n";
/// The format version this build reads and writes.
/// Format 2: the trees break ties between equal split coordinates by photon index
/// ([`super::kdtree`]), so a format-1 file's trees are not what this build would make.
pub const VERSION: u32 = 2;
/// Bytes of one stored photon (12 `f32` and its axis byte).
const PHOTON_BYTES: u64 = 12 * 4 + 1;
/// Most photon passes of one map a file may hold.
const MAX_PASSES: u32 = 1 << 16;

/// One map as a file keeps it.
#[derive(Debug, Clone)]
pub struct StoredMap {
    /// The photons (a built kd-tree); the first pass of a progressive map.
    pub map: PhotonMap,
    /// The later passes of a progressive map, in order (empty: one pass).
    pub later: Vec<PhotonMap>,
    /// Photons emitted to build it, over all passes.
    pub emitted: u64,
}

/// The maps of one photon pass and the content hash they were traced for.
#[derive(Debug, Clone)]
pub struct StoredMaps {
    /// Content hash of the pass's inputs ([`super::key::photon_key`]).
    pub key: u64,
    /// The caustic map, if the pass built one.
    pub caustics: Option<StoredMap>,
    /// The global map, if the pass built one.
    pub global: Option<StoredMap>,
}

/// Why a photon map file could not be read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PhotonFileError {
    /// The file does not start with [`MAGIC`].
    NotAPhotonMap,
    /// Another format version.
    Version(u32),
    /// The file ends before its contents do.
    Truncated,
    /// The checksum does not match the contents.
    Checksum,
    /// A value no writer produces (named).
    Invalid(&'static str),
}

impl std::fmt::Display for PhotonFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NotAPhotonMap => write!(f, "not a stagelight photon map file"),
            Self::Version(v) => write!(
                f,
                "photon map format {v}, but this stagelight reads format {VERSION}"
            ),
            Self::Truncated => write!(f, "the file is truncated"),
            Self::Checksum => write!(f, "the checksum does not match (the file is corrupt)"),
            Self::Invalid(what) => write!(f, "invalid {what}"),
        }
    }
}

/// Encodes `maps` (deterministic: the same maps give the same bytes).
pub fn encode(maps: &StoredMaps) -> Vec<u8> {
    let photons: usize = [&maps.caustics, &maps.global]
        .into_iter()
        .flatten()
        .flat_map(|m| std::iter::once(&m.map).chain(&m.later))
        .map(PhotonMap::len)
        .sum();
    let mut out = Vec::with_capacity(64 + photons * PHOTON_BYTES as usize);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&VERSION.to_le_bytes());
    out.extend_from_slice(&maps.key.to_le_bytes());
    let present = u32::from(maps.caustics.is_some()) | (u32::from(maps.global.is_some()) << 1);
    out.extend_from_slice(&present.to_le_bytes());
    for stored in [&maps.caustics, &maps.global].into_iter().flatten() {
        out.extend_from_slice(&stored.emitted.to_le_bytes());
        out.extend_from_slice(&(1 + stored.later.len() as u32).to_le_bytes());
        for map in std::iter::once(&stored.map).chain(&stored.later) {
            out.extend_from_slice(&(map.len() as u64).to_le_bytes());
            for p in map.photons() {
                for v in [p.position, p.power, p.incoming, p.normal] {
                    for x in v.to_array() {
                        out.extend_from_slice(&x.to_le_bytes());
                    }
                }
            }
            out.extend_from_slice(map.axes());
        }
    }
    let sum = Fnv64::default().bytes(&out).finish();
    out.extend_from_slice(&sum.to_le_bytes());
    out
}

/// The content hash a file was written for, read from its header without checking the rest
/// (`None`: not a photon map file of this version).
pub fn peek_key(bytes: &[u8]) -> Option<u64> {
    let mut r = Reader { bytes, at: 0 };
    r.header().ok()
}

/// Decodes a file written by [`encode`].
pub fn decode(bytes: &[u8]) -> Result<StoredMaps, PhotonFileError> {
    if bytes.len() < MAGIC.len() || !bytes.starts_with(MAGIC) {
        return Err(PhotonFileError::NotAPhotonMap);
    }
    let (body, sum) = bytes
        .split_last_chunk::<8>()
        .ok_or(PhotonFileError::Truncated)?;
    let mut r = Reader { bytes: body, at: 0 };
    let key = r.header()?;
    let present = r.u32()?;
    if present > 3 {
        return Err(PhotonFileError::Invalid("map list"));
    }
    if Fnv64::default().bytes(body).finish() != u64::from_le_bytes(*sum) {
        // A short file fails here too; say which it is when the sizes tell.
        r.maps(present)?;
        return Err(PhotonFileError::Checksum);
    }
    let (caustics, global) = r.maps(present)?;
    if r.at != body.len() {
        return Err(PhotonFileError::Invalid(
            "file length (bytes after the last map)",
        ));
    }
    Ok(StoredMaps {
        key,
        caustics,
        global,
    })
}

/// A cursor over the file's bytes.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8], PhotonFileError> {
        let end = self.at.checked_add(n).ok_or(PhotonFileError::Truncated)?;
        let s = self
            .bytes
            .get(self.at..end)
            .ok_or(PhotonFileError::Truncated)?;
        self.at = end;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, PhotonFileError> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self) -> Result<u64, PhotonFileError> {
        let b = self.take(8)?;
        let mut a = [0u8; 8];
        a.copy_from_slice(b);
        Ok(u64::from_le_bytes(a))
    }

    fn vec3(&mut self) -> Result<Vec3, PhotonFileError> {
        let b = self.take(12)?;
        let f = |i: usize| f32::from_le_bytes([b[i], b[i + 1], b[i + 2], b[i + 3]]);
        Ok(Vec3::new(f(0), f(4), f(8)))
    }

    /// Magic and version; returns the content hash.
    fn header(&mut self) -> Result<u64, PhotonFileError> {
        if self.take(MAGIC.len()).ok() != Some(MAGIC) {
            return Err(PhotonFileError::NotAPhotonMap);
        }
        let version = self.u32()?;
        if version != VERSION {
            return Err(PhotonFileError::Version(version));
        }
        self.u64()
    }

    fn maps(
        &mut self,
        present: u32,
    ) -> Result<(Option<StoredMap>, Option<StoredMap>), PhotonFileError> {
        let caustics = if present & 1 != 0 {
            Some(self.map()?)
        } else {
            None
        };
        let global = if present & 2 != 0 {
            Some(self.map()?)
        } else {
            None
        };
        Ok((caustics, global))
    }

    fn map(&mut self) -> Result<StoredMap, PhotonFileError> {
        let emitted = self.u64()?;
        let passes = self.u32()?;
        if passes == 0 || passes > MAX_PASSES {
            return Err(PhotonFileError::Invalid("number of photon passes"));
        }
        let map = self.tree()?;
        let later = (1..passes)
            .map(|_| self.tree())
            .collect::<Result<Vec<_>, _>>()?;
        Ok(StoredMap {
            map,
            later,
            emitted,
        })
    }

    fn tree(&mut self) -> Result<PhotonMap, PhotonFileError> {
        let n = self.u64()?;
        let left = (self.bytes.len() - self.at) as u64;
        if n.checked_mul(PHOTON_BYTES).is_none_or(|b| b > left) {
            return Err(PhotonFileError::Truncated);
        }
        let n = n as usize;
        let mut photons = Vec::with_capacity(n);
        for _ in 0..n {
            let photon = Photon {
                position: self.vec3()?,
                power: self.vec3()?,
                incoming: self.vec3()?,
                normal: self.vec3()?,
            };
            let values = [
                photon.position,
                photon.power,
                photon.incoming,
                photon.normal,
            ];
            if !values.iter().all(|v| v.is_finite()) {
                return Err(PhotonFileError::Invalid("photon (a value is not finite)"));
            }
            photons.push(photon);
        }
        let axes = self.take(n)?.to_vec();
        PhotonMap::from_tree(photons, axes).ok_or(PhotonFileError::Invalid("kd-tree split axis"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn maps() -> StoredMaps {
        let photon = |i: usize| Photon {
            position: Vec3::new(i as f32 * 0.5, (i % 3) as f32, -(i as f32)),
            power: Vec3::new(0.1, 0.2, 0.3) * (i + 1) as f32,
            incoming: Vec3::Z,
            normal: Vec3::Y,
        };
        StoredMaps {
            key: 0x0123_4567_89ab_cdef,
            caustics: Some(StoredMap {
                map: PhotonMap::build((0..37).map(photon).collect()),
                later: vec![PhotonMap::build((3..9).map(photon).collect())],
                emitted: 1000,
            }),
            global: None,
        }
    }

    #[test]
    fn maps_round_trip_with_the_same_tree_and_the_same_bytes() {
        let m = maps();
        let bytes = encode(&m);
        let back = decode(&bytes).unwrap();
        assert_eq!(back.key, m.key);
        assert!(back.global.is_none());
        let (a, b) = (m.caustics.unwrap(), back.caustics.unwrap());
        assert_eq!(a.emitted, b.emitted);
        assert_eq!(a.map.photons(), b.map.photons());
        assert_eq!(a.map.axes(), b.map.axes());
        assert_eq!(a.later.len(), 1);
        assert_eq!(a.later[0].photons(), b.later[0].photons());
        assert_eq!(encode(&decode(&bytes).unwrap()), bytes);
        assert_eq!(peek_key(&bytes), Some(0x0123_4567_89ab_cdef));
    }

    #[test]
    fn every_truncation_and_every_flipped_byte_is_an_error() {
        let bytes = encode(&maps());
        for len in 0..bytes.len() {
            assert!(decode(&bytes[..len]).is_err(), "truncated at {len}");
        }
        assert_eq!(
            decode(&bytes[..bytes.len() - 20]).unwrap_err(),
            PhotonFileError::Truncated
        );
        for at in (0..bytes.len()).step_by(7) {
            let mut bad = bytes.clone();
            bad[at] ^= 0x40;
            assert!(decode(&bad).is_err(), "flipped byte {at}");
        }
    }

    #[test]
    fn a_huge_photon_count_is_refused_before_allocating() {
        let mut bytes = encode(&maps());
        let count_at = MAGIC.len() + 4 + 8 + 4 + 8 + 4;
        bytes[count_at..count_at + 8].copy_from_slice(&u64::MAX.to_le_bytes());
        assert_eq!(decode(&bytes).unwrap_err(), PhotonFileError::Truncated);
    }

    #[test]
    fn other_files_and_versions_are_named() {
        assert_eq!(
            decode(b"P3\n2 2\n255\n").unwrap_err(),
            PhotonFileError::NotAPhotonMap
        );
        let mut bytes = encode(&maps());
        bytes[MAGIC.len()..MAGIC.len() + 4].copy_from_slice(&7u32.to_le_bytes());
        assert_eq!(decode(&bytes).unwrap_err(), PhotonFileError::Version(7));
        assert_eq!(
            PhotonFileError::Version(7).to_string(),
            "photon map format 7, but this stagelight reads format 2"
        );
    }
}
