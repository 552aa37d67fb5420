//! The image a baked glTF (`--write-gltf`) embeds for each ambient occlusion or lightmap
//! output. A PNG output is embedded byte for byte. Core glTF images are PNG or JPEG only,
//! so an EXR output (the EXR file stays as written) is embedded as a 16-bit PNG made from
//! the same texels: the AO linear (the occlusion texture reads its red channel; glTF 2.0
//! §3.9.2–3.9.3 ask sRGB and 8 bits only of the base colour and emissive textures), a lightmap
//! divided by its largest value and encoded as PNG lightmaps are (sRGB), with that value in
//! its `lightmapFactor`, so `lightmapFactor × texel` is the lightmap's value before its
//! `scale` for either format. Nothing here depends on the thread count: the texels are the
//! bake's, the largest value a fold in texel order.

use super::glb_build::TextureSlot;
use super::TexelImage;
use crate::components::{BakeFormat, BakeTarget};

/// What the baked glTF embeds for `target`, whose texels are `img` and whose encoded file
/// is `file`: the material slot and the PNG bytes; none for kinds that fill no slot
/// (normals, positions, albedo) and per-vertex targets.
pub fn gltf_texture(
    target: &BakeTarget,
    img: &TexelImage,
    file: &[u8],
) -> Result<Option<(TextureSlot, Vec<u8>)>, String> {
    let Some(slot) = TextureSlot::of(&target.kind) else {
        return Ok(None);
    };
    match (target.format, slot) {
        (BakeFormat::Png8 | BakeFormat::Png16, _) => Ok(Some((slot, file.to_vec()))),
        (BakeFormat::Ply, _) => Ok(None),
        (BakeFormat::Exr, TextureSlot::Occlusion) => Ok(Some((slot, img.encode_png(true, false)?))),
        (BakeFormat::Exr, TextureSlot::Lightmap { factor }) => {
            let peak = largest_value(img);
            let normalised = TexelImage {
                texels: img.texels.iter().map(|t| *t / peak).collect(),
                ..img.clone()
            };
            let slot = TextureSlot::Lightmap {
                factor: factor * f64::from(peak),
            };
            Ok(Some((slot, normalised.encode_png(true, true)?)))
        }
    }
}

/// The largest finite channel value of `img`'s texels, or 1 when none is positive (an
/// all-black lightmap is written as it is).
pub fn largest_value(img: &TexelImage) -> f32 {
    let peak = img
        .texels
        .iter()
        .flat_map(|t| t.to_array())
        .filter(|v| v.is_finite())
        .fold(0.0f32, f32::max);
    if peak > 0.0 {
        peak
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::components::BakeKind;
    use crate::image_io::png_codec::{decode_png, Samples};

    fn target(kind: BakeKind, format: BakeFormat) -> BakeTarget {
        BakeTarget {
            kind,
            format,
            file: None,
            denoise: None,
        }
    }

    fn image(values: &[f32]) -> TexelImage {
        let mut img = TexelImage::new(values.len() as u32, 1);
        img.texels = values.iter().map(|&v| Vec3::splat(v)).collect();
        img.valid = vec![true; values.len()];
        img
    }

    /// An EXR lightmap of largest value 4 at `scale: 0.5` is written divided by 4 (sRGB:
    /// 1 → 65535, 0 → 0) with `lightmapFactor` 4 / 0.5 = 8; an all-black one keeps factor
    /// 1 / scale; AO is linear: 0.25 → round(0.25 · 65535) = 16384.
    #[test]
    fn exr_outputs_become_sixteen_bit_pngs() {
        let lightmap = BakeKind::Lightmap {
            indirect: false,
            samples: 1,
            max_depth: 0,
            store: crate::components::LightmapStore::Irradiance,
            scale: 0.5,
        };
        let t = target(lightmap, BakeFormat::Exr);
        let (slot, png) = gltf_texture(&t, &image(&[4.0, 0.0]), b"exr")
            .unwrap()
            .unwrap();
        assert_eq!(slot, TextureSlot::Lightmap { factor: 8.0 });
        let d = decode_png(&png).unwrap();
        assert_eq!(
            d.samples,
            Samples::Sixteen(vec![65535, 65535, 65535, 0, 0, 0])
        );
        let (slot, _) = gltf_texture(&t, &image(&[0.0]), b"exr").unwrap().unwrap();
        assert_eq!(slot, TextureSlot::Lightmap { factor: 2.0 });
        let ao = target(
            BakeKind::AmbientOcclusion {
                samples: 4,
                max_distance: f32::INFINITY,
                bent_normals: false,
            },
            BakeFormat::Exr,
        );
        let (slot, png) = gltf_texture(&ao, &image(&[0.25]), b"exr").unwrap().unwrap();
        assert_eq!(slot, TextureSlot::Occlusion);
        let d = decode_png(&png).unwrap();
        assert_eq!(d.samples, Samples::Sixteen(vec![16384; 3]));
        // A PNG output is embedded as its file.
        let png_ao = target(ao.kind.clone(), BakeFormat::Png8);
        assert_eq!(
            gltf_texture(&png_ao, &image(&[0.25]), b"file").unwrap(),
            Some((TextureSlot::Occlusion, b"file".to_vec()))
        );
    }
}
