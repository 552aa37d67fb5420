//! What happens to a texture request's baked images between evaluation and encoding, in
//! this order: texel-space denoising of the outputs that ask for it ([`super::denoise`], on
//! the texels baked from the surface only), dilation `padding` times ([`super::dilate`]),
//! and the least-squares seam stitch of the AO and lightmap outputs ([`super::stitch`]),
//! measured before and after by the seam metric ([`super::seams`]).

use super::denoise::{denoise, guide};
use super::report::SeamReport;
use super::request::PreparedBake;
use super::seams::{find_seams, seam_difference};
use super::stitch::stitch;
use super::TexelImage;
use crate::components::{BakeKind, TriMesh};

/// What finishing did: texels filled by dilation, and the seam metric (for requests with an
/// AO or lightmap output).
pub struct Finished {
    /// Texels filled by dilation (of the last image).
    pub dilated: u64,
    /// Seams and the difference across them.
    pub seams: Option<SeamReport>,
}

/// Whether a kind is a noisy estimate whose seams are stitched.
fn stitched_kind(kind: &BakeKind) -> bool {
    matches!(
        kind,
        BakeKind::AmbientOcclusion { .. } | BakeKind::Lightmap { .. }
    )
}

/// Denoises, dilates and stitches the images of texture request `p` (aligned with its
/// targets; a trailing bent-normal image is dilated only). `baked` marks the texels baked
/// from the surface.
pub fn finish(
    p: &PreparedBake,
    mesh: &TriMesh,
    images: &mut [TexelImage],
    baked: Option<&[bool]>,
) -> Finished {
    let targets = &p.request.targets;
    if let Some(baked) = baked {
        if targets.iter().any(|t| t.denoise.is_some()) {
            let g = guide(&p.coverage, mesh, &p.uvs);
            for (target, img) in targets.iter().zip(images.iter_mut()) {
                if let Some(settings) = target.denoise {
                    *img = denoise(img, baked, &g, settings);
                }
            }
        }
    }
    let mut dilated = 0;
    for img in images.iter_mut() {
        dilated = super::dilate::dilate(img, p.request.padding);
    }
    let first = targets.iter().position(|t| stitched_kind(&t.kind));
    let seams = first.map(|first| {
        let (w, h) = (p.coverage.width, p.coverage.height);
        let seams = find_seams(&mesh.positions, &mesh.triangles, &p.uvs, w, h);
        let before = seam_difference(&images[first], &seams);
        let mut changed = 0;
        if p.request.stitch_seams {
            for (target, img) in targets.iter().zip(images.iter_mut()) {
                if stitched_kind(&target.kind) {
                    changed += stitch(img, &seams);
                }
            }
        }
        let after = seam_difference(&images[first], &seams);
        SeamReport {
            edges: seams.edges as u64,
            samples: seams.pairs.len() as u64,
            mean_before: before.mean,
            max_before: before.max,
            mean_after: after.mean,
            max_after: after.max,
            stitched: p.request.stitch_seams,
            texels_changed: changed,
        }
    });
    Finished { dilated, seams }
}
