//! Baked values a PNG output cannot hold. PNG stores [0, 1] per channel (normals mapped
//! there from [−1, 1]), so a texel with a channel above 1 (a lightmap brighter than white, a
//! position beyond the unit cube) or below 0 is clipped when encoded. [`clipped_texels`]
//! counts them and [`clip_warning`] words the warning, located at the request in the scene.

use super::TexelImage;
use crate::components::{BakeFormat, BakeKind, BakeTarget, LightmapStore};

/// The texels of one output that its PNG clips.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clipped {
    /// Texels written (baked or dilated) with a channel outside [0, 1] by more than half a
    /// code step of the PNG.
    pub texels: u64,
    /// Texels written.
    pub of: u64,
    /// The largest channel value written.
    pub max: f32,
    /// The smallest channel value written.
    pub min: f32,
}

/// The texels of `img` that `target`'s PNG clips; `None` for EXR, normals (mapped from
/// [−1, 1]) and an output none of whose texels is clipped.
pub fn clipped_texels(img: &TexelImage, target: &BakeTarget) -> Option<Clipped> {
    let png = matches!(target.format, BakeFormat::Png8 | BakeFormat::Png16);
    if !png || matches!(target.kind, BakeKind::Normals { .. }) {
        return None;
    }
    // Half a code step of the format: a value that encodes to the code of 1 (or 0), such
    // as a white sky's E / π = 1 off by rounding, is not clipped.
    let slack = if target.format == BakeFormat::Png16 {
        0.5 / 65535.0
    } else {
        0.5 / 255.0
    };
    let mut c = Clipped {
        texels: 0,
        of: 0,
        max: f32::NEG_INFINITY,
        min: f32::INFINITY,
    };
    for (texel, _) in img.texels.iter().zip(&img.valid).filter(|(_, &v)| v) {
        c.of += 1;
        c.max = c.max.max(texel.max_element());
        c.min = c.min.min(texel.min_element());
        if texel.max_element() > 1.0 + slack || texel.min_element() < -slack {
            c.texels += 1;
        }
    }
    (c.texels > 0).then_some(c)
}

/// The warning (message, help) for `clipped` texels of the output written to `file`.
pub fn clip_warning(clipped: &Clipped, target: &BakeTarget, file: &str) -> (String, String) {
    let depth = if target.format == BakeFormat::Png16 {
        "16-bit"
    } else {
        "8-bit"
    };
    let range = if clipped.min < 0.0 {
        format!("values from {:.3} to {:.3}", clipped.min, clipped.max)
    } else {
        format!("largest value {:.3}", clipped.max)
    };
    let message = format!(
        "{} of {} texels of \"{file}\" lie outside the {depth} PNG's range [0, 1] and were clipped ({range})",
        clipped.texels, clipped.of
    );
    let exr = "write it as EXR (`format: Exr`) to keep the full range";
    let help = match target.kind {
        BakeKind::Lightmap {
            store: LightmapStore::Irradiance,
            ..
        } => format!(
            "{exr}, or store `Lightmap(store: IrradianceOverPi)` (E / π: 1 under a white sky of radiance 1)"
        ),
        BakeKind::Lightmap { scale, .. } if clipped.max > 1.0 => format!(
            "{exr}, or lower the lightmap's `scale` (now {scale}; {} fits the largest value), which multiplies the stored value (a glTF copy's `lightmapFactor` undoes it)",
            two_digits_down(f64::from(scale) / f64::from(clipped.max))
        ),
        _ => exr.to_string(),
    };
    (message, help)
}

/// `x > 0` rounded down to two significant digits, written without float noise.
fn two_digits_down(x: f64) -> String {
    let exponent = x.log10().floor() as i32 - 1;
    let digits = (x / 10f64.powi(exponent)).floor();
    let decimals = (-exponent).max(0) as usize;
    format!("{:.*}", decimals, digits * 10f64.powi(exponent))
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn image(values: &[f32], valid: &[bool]) -> TexelImage {
        TexelImage {
            width: values.len() as u32,
            height: 1,
            texels: values.iter().map(|&v| Vec3::splat(v)).collect(),
            valid: valid.to_vec(),
        }
    }

    fn target(kind: BakeKind, format: BakeFormat) -> BakeTarget {
        BakeTarget {
            kind,
            format,
            file: None,
            denoise: None,
        }
    }

    /// Only written texels count; EXR and normals never clip.
    #[test]
    fn counts_written_texels_outside_the_unit_range() {
        let img = image(&[0.5, 1.5, 3.0, 9.0], &[true, true, true, false]);
        let ao = target(BakeKind::Positions, BakeFormat::Png8);
        assert_eq!(
            clipped_texels(&img, &ao),
            Some(Clipped {
                texels: 2,
                of: 3,
                max: 3.0,
                min: 0.5
            })
        );
        assert_eq!(
            clipped_texels(&img, &target(BakeKind::Positions, BakeFormat::Exr)),
            None
        );
        let inside = image(&[0.0, 1.0, 1.0 + 1e-6, -1e-6], &[true; 4]);
        assert_eq!(clipped_texels(&inside, &ao), None);
    }

    /// A lightmap's help names the `scale` that fits its largest value.
    #[test]
    fn a_scaled_lightmap_is_told_the_scale_that_fits() {
        let kind = BakeKind::Lightmap {
            indirect: true,
            samples: 4,
            max_depth: 2,
            store: LightmapStore::IrradianceOverPi,
            scale: 0.5,
        };
        let clipped = Clipped {
            texels: 3,
            of: 10,
            max: 1.04,
            min: 0.2,
        };
        let (message, help) = clip_warning(&clipped, &target(kind, BakeFormat::Png8), "a.png");
        assert_eq!(
            message,
            "3 of 10 texels of \"a.png\" lie outside the 8-bit PNG's range [0, 1] and were clipped (largest value 1.040)"
        );
        assert_eq!(
            help,
            "write it as EXR (`format: Exr`) to keep the full range, or lower the lightmap's `scale` (now 0.5; 0.48 fits the largest value), which multiplies the stored value (a glTF copy's `lightmapFactor` undoes it)"
        );
        assert_eq!(two_digits_down(0.000_123_9), "0.00012");
        assert_eq!(two_digits_down(37.9), "37");
    }
}
