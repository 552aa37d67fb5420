//! A pass's stored photons as its work items made them: one vector per work item, in
//! photon-index order. The map's kd-tree is built from the parts directly
//! ([`super::PhotonMap::from_parts`] of [`PhotonParts::into_parts`]); concatenating them first copied the whole map once more
//! into fresh pages (28–51 ms of the 1 M-photon `caustics_photons.ron` pass, issue 17).

use super::kdtree::Photon;

/// Stored photons in order, held as the work items' vectors (empty ones are dropped).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PhotonParts {
    parts: Vec<Vec<Photon>>,
}

impl PhotonParts {
    /// No photons.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends the photons of `part` after the ones held.
    pub fn push(&mut self, part: Vec<Photon>) {
        if !part.is_empty() {
            self.parts.push(part);
        }
    }

    /// Appends the photons of `other` after the ones held.
    pub fn append(&mut self, other: PhotonParts) {
        self.parts.extend(other.parts);
    }

    /// Number of photons.
    pub fn len(&self) -> usize {
        self.parts.iter().map(Vec::len).sum()
    }

    /// True when no photon is held.
    pub fn is_empty(&self) -> bool {
        self.parts.is_empty()
    }

    /// The photons in order, in one vector.
    pub fn into_vec(self) -> Vec<Photon> {
        match self.parts.len() {
            0 => Vec::new(),
            1 => self.parts.into_iter().next().unwrap_or_default(),
            _ => self.parts.concat(),
        }
    }

    /// The work items' vectors, in order, none empty.
    pub fn into_parts(self) -> Vec<Vec<Photon>> {
        self.parts
    }
}

impl From<Vec<Photon>> for PhotonParts {
    fn from(photons: Vec<Photon>) -> Self {
        let mut parts = Self::new();
        parts.push(photons);
        parts
    }
}

impl FromIterator<Vec<Photon>> for PhotonParts {
    fn from_iter<I: IntoIterator<Item = Vec<Photon>>>(iter: I) -> Self {
        let mut parts = Self::new();
        for part in iter {
            parts.push(part);
        }
        parts
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    /// Parts keep their photons in order, drop empty vectors and join back into one vector.
    #[test]
    fn parts_join_in_order() {
        let photon = |x: f32| Photon {
            position: Vec3::splat(x),
            power: Vec3::ONE,
            incoming: Vec3::Z,
            normal: Vec3::Z,
        };
        let all: Vec<Photon> = (0..10).map(|i| photon(i as f32)).collect();
        let mut parts: PhotonParts = [all[..3].to_vec(), Vec::new(), all[3..4].to_vec()]
            .into_iter()
            .collect();
        parts.append(PhotonParts::from(all[4..].to_vec()));
        parts.push(Vec::new());
        assert_eq!((parts.len(), parts.is_empty()), (10, false));
        assert_eq!(parts.clone().into_parts().len(), 3);
        assert_eq!(parts.into_vec(), all);
        assert!(PhotonParts::new().is_empty());
        assert_eq!(PhotonParts::from(Vec::new()).into_vec(), Vec::new());
    }
}
