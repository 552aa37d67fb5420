//! The image textures a scene's shader graphs read: each (file, wrap, encoding) decoded once
//! and shared between materials, and each counted against the run's memory budget from its
//! file's header before it is decoded. A small, highly compressed file that would decode to
//! more than the budget (alone, or with the textures read before it) is a located refusal,
//! not an allocation.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use crate::memory_budget::{human, Budget};
use crate::shading::texture::image::{Footprint, Texture, UvWrap};

/// A texture's file, wrap and explicit sRGB choice.
pub(super) type TextureKey = (PathBuf, UvWrap, Option<bool>);

/// The textures read so far and the bytes they take.
pub struct Textures {
    /// By key; `None` when the file was unreadable or refused.
    decoded: HashMap<TextureKey, Option<Arc<Texture>>>,
    /// The run's memory budget.
    budget: Budget,
    /// Bytes of the textures admitted so far.
    admitted: u64,
}

impl Textures {
    /// No textures yet, under `budget`.
    pub fn new(budget: Budget) -> Self {
        Self {
            decoded: HashMap::new(),
            budget,
            admitted: 0,
        }
    }

    /// The texture read for `key` before (`Some(None)`: it could not be).
    pub(super) fn get(&self, key: &TextureKey) -> Option<&Option<Arc<Texture>>> {
        self.decoded.get(key)
    }

    /// Keeps what reading `key` gave.
    pub(super) fn insert(&mut self, key: TextureKey, texture: Option<Arc<Texture>>) {
        self.decoded.insert(key, texture);
    }

    /// Counts a texture of `size` read from the file written as `name` against the budget,
    /// or gives the message and help of its refusal (then nothing is counted).
    pub(super) fn admit(&mut self, name: &str, size: &Footprint) -> Result<(), (String, String)> {
        let total = self.admitted.saturating_add(size.bytes);
        if self.budget.fits(total) {
            self.admitted = total;
            return Ok(());
        }
        let what = format!(
            "image \"{name}\": the texels of a {}×{} image need about {}",
            size.width,
            size.height,
            human(size.bytes)
        );
        let together = if self.budget.fits(size.bytes) {
            format!(
                ", and the scene's image textures together about {}",
                human(total)
            )
        } else {
            String::new()
        };
        Err((
            format!(
                "{what}{together}, more than the memory budget of {}",
                self.budget
            ),
            "use a smaller image (or fewer), or raise the budget with --memory-limit BYTES".into(),
        ))
    }
}
