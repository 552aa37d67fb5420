//! The image textures a scene's shader graphs read: each (file, wrap, encoding) decoded once
//! and shared between materials, and each counted against the run's memory budget from its
//! file's header before it is decoded. A small, highly compressed file that would decode to
//! more than the budget (alone, or with the textures read before it) is a located refusal,
//! not an allocation. The decoded ones are listed ([`DecodedTexture`]) so that the loader
//! spawns them for the run-wide memory estimate, which adds them to the camera, the
//! geometry, photons and bakes.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use crate::components::{DecodedImage, ImageContent};
use crate::memory_budget::{human, Budget};
use crate::scene::diagnostics::SourcePos;
use crate::shading::texture::image::{decoded_bytes, Footprint, Texture, UvWrap};

/// A texture's file, wrap and explicit sRGB choice.
pub(super) type TextureKey = (PathBuf, UvWrap, Option<bool>);

/// An image texture that was decoded: the file as written, where it is written first, and
/// what its texels take.
#[derive(Debug, Clone)]
pub struct DecodedTexture {
    /// The `file` value, as written.
    pub name: String,
    /// Where that value is.
    pub at: SourcePos,
    /// Its size once decoded.
    pub image: DecodedImage,
}

/// The textures read so far and the bytes they take.
pub struct Textures {
    /// By key; `None` when the file was unreadable or refused.
    decoded: HashMap<TextureKey, Option<Arc<Texture>>>,
    /// Every texture decoded, in the order read.
    listed: Vec<DecodedTexture>,
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
            listed: Vec::new(),
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

    /// Lists `texture`, decoded from the file written as `name` at `at`.
    pub(super) fn list(&mut self, name: &str, at: SourcePos, texture: &Texture) {
        self.listed.push(DecodedTexture {
            name: name.to_string(),
            at,
            image: DecodedImage {
                width: texture.width,
                height: texture.height,
                bytes: decoded_bytes(texture),
                content: ImageContent::Texture,
            },
        });
    }

    /// Every texture decoded, in the order read.
    pub fn listed(&self) -> &[DecodedTexture] {
        &self.listed
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
            "image \"{name}\": {} need about {}",
            ImageContent::Texture.describe(size.width, size.height),
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
