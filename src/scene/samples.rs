//! Checks the `samples` option: a fixed count, or adaptive `(min, max, contrast)`.

use super::checker::Checker;
use super::desc::SamplesDesc;
use crate::settings::AdaptiveSamples;

/// The uniform sample count and the adaptive settings of `samples` (errors recorded at
/// `path`; the returned values are then placeholders).
pub fn samples(ck: &mut Checker<'_>, path: &str, s: SamplesDesc) -> (u32, Option<AdaptiveSamples>) {
    match s {
        SamplesDesc::Fixed(n) => (count(ck, path, "samples", n, 1), None),
        SamplesDesc::Adaptive { min, max, contrast } => {
            let lo = count(ck, &format!("{path}.min"), "min", min, 1);
            let hi = count(ck, &format!("{path}.max"), "max", max, lo);
            let contrast = ck
                .colour(&format!("{path}.contrast"), "contrast", contrast)
                .map_or(glam::Vec3::ZERO, |c| c.as_vec3());
            (
                lo,
                Some(AdaptiveSamples {
                    min: lo,
                    max: hi.max(lo),
                    contrast,
                }),
            )
        }
    }
}

/// A count in `[at_least, u32::MAX]`.
fn count(ck: &mut Checker<'_>, path: &str, what: &str, n: u64, at_least: u32) -> u32 {
    if n < u64::from(at_least) {
        let bound = if what == "max" {
            format!("min ({at_least})")
        } else {
            at_least.to_string()
        };
        ck.error(path, format!("{what} must be at least {bound}, found {n}"));
        return at_least;
    }
    u32::try_from(n).unwrap_or_else(|_| {
        ck.error(
            path,
            format!("{what} {n} is too large (at most {})", u32::MAX),
        );
        at_least
    })
}
