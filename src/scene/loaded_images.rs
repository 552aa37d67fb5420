//! The images the loader decodes outside shader graphs: the scene environment's lat-long
//! map, materials' environment maps and displacement images. Each is counted against the
//! run's memory budget from its file's header before it is decoded, so a file that would
//! decode past the budget is a located refusal at its `file` (worded as an image texture's),
//! not an allocation; each one decoded is listed, and the loader spawns it
//! ([`DecodedImage`]) for the run-wide memory estimate, which adds it to the textures, the
//! camera, the geometry, photons and bakes. (Image textures keep their own list:
//! `nodes::textures`.)

use crate::components::{DecodedImage, ImageContent};
use crate::memory_budget::{human, Budget};

use super::message::SourcePos;

/// A decoded image: the file as written, where it is written, and what it takes.
#[derive(Debug, Clone)]
pub struct LoadedImage {
    /// The `file` value, as written.
    pub name: String,
    /// Where that value is.
    pub at: SourcePos,
    /// Its size once decoded.
    pub image: DecodedImage,
}

/// The run's memory budget and the images decoded under it.
#[derive(Debug, Default)]
pub struct LoadedImages {
    budget: Budget,
    listed: Vec<LoadedImage>,
}

impl LoadedImages {
    /// No images yet, under `budget`.
    pub fn new(budget: Budget) -> Self {
        Self {
            budget,
            listed: Vec::new(),
        }
    }

    /// Whether an image of `width × height` read as `content` from the file written as
    /// `name`, whose reading takes `bytes` at its peak, fits the budget; else the message
    /// and help of its refusal.
    pub fn admit(
        &self,
        name: &str,
        (width, height): (u32, u32),
        content: ImageContent,
        bytes: u64,
    ) -> Result<(), (String, String)> {
        if self.budget.fits(bytes) {
            return Ok(());
        }
        Err((
            format!(
                "image \"{name}\": {} need about {}, more than the memory budget of {}",
                content.describe(width, height),
                human(bytes),
                self.budget
            ),
            "use a smaller image (or fewer), or raise the budget with --memory-limit BYTES".into(),
        ))
    }

    /// Lists `image`, decoded from the file written as `name` at `at`.
    pub fn list(&mut self, name: &str, at: SourcePos, image: DecodedImage) {
        self.listed.push(LoadedImage {
            name: name.to_string(),
            at,
            image,
        });
    }

    /// Every image decoded, in the order read.
    pub fn listed(&self) -> &[LoadedImage] {
        &self.listed
    }
}
