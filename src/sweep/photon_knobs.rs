//! The photon knobs of `stagelight sweep` that are not plain numbers of every map:
//! `passes` (progressive photon mapping of the caustic map) and `filter` (the estimate filter
//! of every photon map): parsing their values and applying one.

use crate::settings::{PhotonFilter, ProgressiveSettings, RenderSettings};

/// α of a caustic map that the `passes` knob makes progressive (Hachisuka's 0.7).
pub const DEFAULT_ALPHA: f32 = 0.7;

/// What the `filter` knob's values may be.
pub const FILTER_VALUES: &str = "box, cone, cone:K (K ≥ 1) or gauss";

/// Parses the `filter` knob's values: `box`, `cone` (k = 1.1), `cone:K` (K ≥ 1), `gauss`;
/// the first value that is none of them is the error.
pub fn parse_filters(values: &str) -> Result<Vec<PhotonFilter>, String> {
    values
        .split(',')
        .map(|v| {
            let v = v.trim();
            let bad = || v.to_string();
            match v.to_ascii_lowercase().as_str() {
                "box" => Ok(PhotonFilter::Box),
                "gauss" => Ok(PhotonFilter::Gauss),
                "cone" => Ok(PhotonFilter::Cone { k: 1.1 }),
                other => {
                    let k: f32 = other
                        .strip_prefix("cone:")
                        .and_then(|k| k.parse().ok())
                        .ok_or_else(bad)?;
                    if k.is_finite() && (1.0..=1e6).contains(&k) {
                        Ok(PhotonFilter::Cone { k })
                    } else {
                        Err(bad())
                    }
                }
            }
        })
        .collect()
}

/// A filter as the knob writes it.
pub fn filter_label(f: PhotonFilter) -> String {
    match f {
        PhotonFilter::Box => "box".into(),
        PhotonFilter::Gauss => "gauss".into(),
        PhotonFilter::Cone { k } => format!("cone:{k}"),
    }
}

/// Sets the caustic map's progressive passes (keeping its α, or [`DEFAULT_ALPHA`]).
pub fn apply_passes(settings: &mut RenderSettings, passes: u32) {
    if let Some(c) = &mut settings.photons.caustics {
        let alpha = c.progressive.map_or(DEFAULT_ALPHA, |p| p.alpha);
        c.progressive = Some(ProgressiveSettings { passes, alpha });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::PhotonMapSettings;

    #[test]
    fn filters_parse_and_print_back() {
        let f = parse_filters("box, Cone,cone:2,gauss").unwrap();
        assert_eq!(
            f,
            [
                PhotonFilter::Box,
                PhotonFilter::Cone { k: 1.1 },
                PhotonFilter::Cone { k: 2.0 },
                PhotonFilter::Gauss
            ]
        );
        let labels: Vec<String> = f.into_iter().map(filter_label).collect();
        assert_eq!(labels, ["box", "cone:1.1", "cone:2", "gauss"]);
        for bad in ["cone:0.5", "tent", "cone:x"] {
            assert_eq!(parse_filters(&format!("box,{bad}")), Err(bad.to_string()));
        }
    }

    #[test]
    fn passes_make_the_caustic_map_progressive_and_keep_its_alpha() {
        let map = PhotonMapSettings {
            photons: 10,
            radius: 0.0,
            gather: 8,
            final_gather: 1,
            precompute: true,
            aim: true,
            filter: PhotonFilter::Box,
            progressive: None,
        };
        let mut s = RenderSettings::default();
        s.photons.caustics = Some(map);
        s.photons.global_illumination = Some(map);
        apply_passes(&mut s, 8);
        let p = s.photons.caustics.unwrap().progressive.unwrap();
        assert_eq!((p.passes, p.alpha), (8, DEFAULT_ALPHA));
        assert!(s.photons.global_illumination.unwrap().progressive.is_none());
        s.photons.caustics.as_mut().unwrap().progressive = Some(ProgressiveSettings {
            passes: 2,
            alpha: 0.5,
        });
        apply_passes(&mut s, 4);
        let p = s.photons.caustics.unwrap().progressive.unwrap();
        assert_eq!((p.passes, p.alpha), (4, 0.5));
    }
}
