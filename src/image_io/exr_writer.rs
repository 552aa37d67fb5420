//! OpenEXR encoding of frame buffers: linear f32 channels for every pass the frame buffers
//! hold (`R G B A`, `Z`, `N.X N.Y N.Z`, the component passes' `emission.R …`, u32 ids), one
//! layer, lossless compression, beside channels the caller derived (the camera-space passes'
//! `Z`, `N.X …`, `P.X …` and the contour layer). Only [`crate::exr_output`], which derives
//! the camera-space passes from the camera, calls it: every camera output goes through there.

use exr::prelude::*;

use crate::components::Pass;
use crate::framebuffer::FrameBuffers;

/// Encodes the passes among `passes` that `fb` holds, and the `derived` f32 channels of the
/// same size, into an EXR file in memory; the coverage goes in as channel `A` when `alpha`
/// says so. The camera-space passes are not `fb`'s: they come in `derived`
/// ([`crate::exr_output`] derives them).
pub(crate) fn encode_passes(
    fb: &FrameBuffers,
    passes: &[Pass],
    alpha: bool,
    derived: Vec<(&str, Vec<f32>)>,
) -> std::result::Result<Vec<u8>, String> {
    let mut channels: SmallVec<[AnyChannel<FlatSamples>; 4]> = SmallVec::new();
    let mut add = |name: &str, values: Vec<f32>| {
        channels.push(AnyChannel::new(name, FlatSamples::F32(values)));
    };
    let beauty = passes.contains(&Pass::Beauty);
    if beauty {
        add("R", fb.beauty.iter().map(|c| c.x).collect());
        add("G", fb.beauty.iter().map(|c| c.y).collect());
        add("B", fb.beauty.iter().map(|c| c.z).collect());
    }
    if alpha {
        add("A", fb.alpha.clone());
    }
    if passes.contains(&Pass::Depth) {
        add("Z", fb.depth.clone());
    }
    if passes.contains(&Pass::Normal) {
        add("N.X", fb.normal.iter().map(|n| n.x).collect());
        add("N.Y", fb.normal.iter().map(|n| n.y).collect());
        add("N.Z", fb.normal.iter().map(|n| n.z).collect());
    }
    if fb.components.is_none() && passes.iter().any(|p| p.component().is_some()) {
        return Err("the component passes were not computed for this image".into());
    }
    if let Some(components) = &fb.components {
        for (index, layer) in passes.iter().filter_map(Pass::component) {
            for (channel, pick) in [("R", 0), ("G", 1), ("B", 2)] {
                let values = components.iter().map(|c| c[index][pick]).collect();
                add(&format!("{layer}.{channel}"), values);
            }
        }
    }
    if passes.contains(&Pass::ObjectId) {
        channels.push(AnyChannel::new(
            "id.object",
            FlatSamples::U32(fb.object_id.clone()),
        ));
    }
    if passes.contains(&Pass::MaterialId) {
        channels.push(AnyChannel::new(
            "id.material",
            FlatSamples::U32(fb.material_id.clone()),
        ));
    }
    for (name, values) in derived {
        channels.push(AnyChannel::new(name, FlatSamples::F32(values)));
    }
    let size = (fb.width as usize, fb.height as usize);
    let layer = Layer::new(
        size,
        LayerAttributes::default(),
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels),
    );
    let image = Image::from_layer(layer);
    let mut cursor = std::io::Cursor::new(Vec::new());
    image
        .write()
        .non_parallel()
        .to_buffered(&mut cursor)
        .map_err(|e| e.to_string())?;
    Ok(cursor.into_inner())
}
