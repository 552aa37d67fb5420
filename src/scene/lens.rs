//! Checks a camera's `lens: [...]` list and builds its [`Lenses`] component: thin lenses
//! need a positive aperture (`radius`, or `fstop` with the camera's focal length) and focus
//! distance; at most one projection (`Fisheye`, `Spherical`, `Shift`), and it comes first.

use super::desc::{CameraDesc, LensDesc};
use super::diagnostics::Sources;
use super::validate::{Checker, Item};
use crate::components::{Lens, Lenses};

/// Half the height of 35 mm film, metres: with `fov_y` it fixes the focal length of `fstop`.
const HALF_FILM_HEIGHT: f64 = 0.012;

/// The camera's lenses: `None` when it has none or one is invalid (errors recorded).
pub fn lenses(src: &mut Sources, item: &Item<'_, CameraDesc>) -> Option<Lenses> {
    let c = item.desc;
    if c.lens.is_empty() {
        return None;
    }
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let mut out = Vec::new();
    let mut ok = true;
    for (k, d) in c.lens.iter().enumerate() {
        let path = item.at(&format!(".lens[{k}]"));
        match lens(&mut ck, &path, d, c.fov_y) {
            Some(l) => {
                if l.is_projection() && k > 0 {
                    let help = if out.iter().any(Lens::is_projection) {
                        "a camera has at most one projection lens"
                    } else {
                        "a projection replaces the pinhole, so it must come first in `lens`"
                    };
                    ck.src.error(
                        ck.file,
                        &path,
                        if matches!(l, Lens::Shift { .. }) {
                            "a Shift lens (an off-axis pinhole) must be the first lens"
                        } else {
                            "a projection lens (Fisheye, Spherical, Shift) must be the first lens"
                        },
                        Some(help.into()),
                    );
                    ok = false;
                }
                out.push(l);
            }
            None => ok = false,
        }
    }
    ok.then_some(Lenses(out))
}

fn lens(ck: &mut Checker<'_>, path: &str, d: &LensDesc, fov_y: f64) -> Option<Lens> {
    match *d {
        LensDesc::ThinLens {
            radius,
            fstop,
            focus_distance,
        } => {
            let p = format!("{path}.ThinLens");
            let focus = positive(
                ck,
                &format!("{p}.focus_distance"),
                "focus_distance",
                focus_distance,
            );
            let radius = match (radius, fstop) {
                (Some(r), None) => positive(ck, &format!("{p}.radius"), "radius", r),
                (None, Some(n)) => {
                    let n = positive(ck, &format!("{p}.fstop"), "fstop", n)?;
                    let focal = HALF_FILM_HEIGHT / (fov_y.to_radians() * 0.5).tan();
                    (focal.is_finite() && focal > 0.0).then_some(focal / (2.0 * n))
                }
                (Some(_), Some(_)) | (None, None) => {
                    ck.src.error(
                        ck.file,
                        &p,
                        "a ThinLens needs exactly one of `radius` and `fstop`",
                        Some("e.g. `ThinLens(radius: 0.05, focus_distance: 4.0)`".into()),
                    );
                    None
                }
            };
            Some(Lens::ThinLens {
                radius: radius? as f32,
                focus_distance: focus? as f32,
            })
        }
        LensDesc::Fisheye { fov } => {
            let p = format!("{path}.Fisheye.fov");
            if ck.finite(&p, "fov", fov) && !(fov > 0.0 && fov <= 360.0) {
                ck.error(&p, format!("fov must be in (0, 360] degrees, found {fov}"));
                return None;
            }
            fov.is_finite().then(|| Lens::Fisheye {
                fov: fov.to_radians() as f32,
            })
        }
        LensDesc::Spherical => Some(Lens::Spherical),
        LensDesc::Shift { x, y } => {
            let ok_x = ck.finite(&format!("{path}.Shift.x"), "x", x);
            let ok_y = ck.finite(&format!("{path}.Shift.y"), "y", y);
            (ok_x && ok_y).then_some(Lens::Shift {
                x: x as f32,
                y: y as f32,
            })
        }
    }
}

fn positive(ck: &mut Checker<'_>, path: &str, what: &str, x: f64) -> Option<f64> {
    if !ck.finite(path, what, x) {
        return None;
    }
    if x <= 0.0 {
        ck.error(path, format!("{what} must be positive, found {x}"));
        return None;
    }
    Some(x)
}
