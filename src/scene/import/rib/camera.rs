//! The RIB options that make the camera, its outputs and the render options: `Format`,
//! `Projection`, `ScreenWindow`, `PixelSamples`, `PixelFilter`, `Exposure`, `Imager`
//! (`"background"`, or the tutorial's `"myImager"` as the imager's `pattern`),
//! `Display`, `DepthOfField`, and the camera transformation current at `WorldBegin`.
//!
//! An off-centre `ScreenWindow` becomes a `Shift` lens (an off-axis pinhole), `DepthOfField`
//! a `ThinLens` after it. The camera transformation's uniform scale, dropped from the
//! placement, becomes the camera's `space_scale` (the unit of the `z` and `P` displays).
//!
//! RI spec 3.2 defaults: `Format 640 480 1`, perspective `fov` 90° across the shorter side
//! of the screen window, `PixelSamples 2 2`, `PixelFilter "gaussian" 2 2`, `Exposure 1 1`
//! (no display gamma: 8-bit files hold linear values), no imager, no display.

use glam::{DMat3, DMat4, DVec3};

use super::super::located::Pos;
use crate::scene::camera_rotation::uniform_scale;
use crate::scene::desc::{
    CameraDesc, FilterDesc, ImagerDesc, ImagerPatternDesc, LensDesc, OutputDesc, PassDesc,
    PlacementDesc, SamplesDesc, ToneMapDesc, M4, V3,
};

/// One `Display` output.
#[derive(Debug, Clone)]
pub struct Display {
    /// File name as we write it.
    pub file: String,
    /// Where the name is.
    pub pos: Pos,
    /// Passes.
    pub passes: Vec<PassDesc>,
    /// `Some(false)`: an EXR file whose mode names colour but no alpha (`rgb`, `rgbz`).
    pub beauty_alpha: Option<bool>,
}

/// `DepthOfField`: RISpec 3.2's lens of diameter `focallength / fstop` focused at
/// `focaldistance`, both in camera-space units.
#[derive(Debug, Clone, Copy)]
pub struct DepthOfField {
    /// Aperture radius, `focallength / (2 · fstop)`, camera-space units.
    pub radius: f64,
    /// `focaldistance`, camera-space units.
    pub focus: f64,
    /// Where the request is.
    pub pos: Pos,
    /// Where `focaldistance` is.
    pub focus_pos: Pos,
}

/// The camera options as written so far (`None`: not written, the RI default applies).
#[derive(Debug, Clone, Default)]
pub struct CameraOptions {
    /// `Format xres yres pixelaspect` and where.
    pub format: Option<((u32, u32, f64), Pos)>,
    /// `Projection "perspective" "fov"` value (degrees) and where.
    pub fov: Option<(f64, Pos)>,
    /// Where `Projection` is.
    pub projection: Option<Pos>,
    /// `ScreenWindow left right bottom top` and where.
    pub screen: Option<([f64; 4], Pos)>,
    /// `PixelSamples` product and where.
    pub samples: Option<(u64, Pos)>,
    /// `PixelFilter` as ours and where.
    pub filter: Option<(FilterDesc, Pos)>,
    /// `Exposure gain gamma` and where.
    pub exposure: Option<((f64, f64), Pos)>,
    /// `Imager "background"` colour and where.
    pub background: Option<(V3, Pos)>,
    /// `Imager "myImager"` as the imager's pattern and where its name is.
    pub pattern: Option<(ImagerPatternDesc, Pos)>,
    /// The displays.
    pub displays: Vec<Display>,
    /// `DepthOfField fstop focallength focaldistance` as a thin lens in camera-space units
    /// (`None`: a pinhole — not written, no arguments, or an infinite `fstop`).
    pub depth_of_field: Option<DepthOfField>,
    /// Camera-from-world (the transformation at `WorldBegin`) and where `WorldBegin` is.
    pub camera_from_world: Option<(DMat4, Pos)>,
}

/// The RenderMan-space mirror applied to the world: z → −z when the camera transformation
/// is a proper motion, none when it mirrors already.
pub fn world_mirror(camera_from_world: DMat4) -> DMat4 {
    if camera_from_world.determinant() < 0.0 {
        DMat4::IDENTITY
    } else {
        DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0))
    }
}

/// Row-major rows of a column-vector affine matrix.
pub fn rows(m: DMat4) -> M4 {
    let t = m.transpose().to_cols_array_2d();
    [t[0], t[1], t[2], [0.0, 0.0, 0.0, 1.0]]
}

impl CameraOptions {
    /// The camera (named `camera`) and the paths of its values.
    pub fn camera(&self, world_pos: Pos) -> (CameraDesc, Vec<(String, Pos)>) {
        let mut paths = vec![(String::new(), self.projection.unwrap_or(world_pos))];
        let ((w, h, pixel_aspect), fpos) = self.format.unwrap_or(((640, 480, 1.0), world_pos));
        paths.push((".resolution".into(), fpos));
        let frame_aspect = f64::from(w) * pixel_aspect / f64::from(h);
        let screen = self.screen.map_or_else(
            || {
                if frame_aspect >= 1.0 {
                    [-frame_aspect, frame_aspect, -1.0, 1.0]
                } else {
                    [-1.0, 1.0, -1.0 / frame_aspect, 1.0 / frame_aspect]
                }
            },
            |(s, p)| {
                paths.push((".aspect".into(), p));
                s
            },
        );
        let (fov, fov_pos) = self.fov.unwrap_or((90.0, world_pos));
        let half = (fov.to_radians() / 2.0).tan();
        let top = (screen[3] - screen[2]) / 2.0;
        let fov_y = 2.0 * (half * top).atan().to_degrees();
        paths.push((".fov_y".into(), fov_pos));
        let aspect = (screen[1] - screen[0]) / (screen[3] - screen[2]);
        // An off-centre window is a shifted pinhole, in half-heights of the window.
        let (cx, cy) = ((screen[0] + screen[1]) / 2.0, (screen[2] + screen[3]) / 2.0);
        let lens = if cx != 0.0 || cy != 0.0 {
            if let Some((_, p)) = self.screen {
                paths.push((".lens[0]".into(), p));
            }
            vec![LensDesc::Shift {
                x: cx / top,
                y: cy / top,
            }]
        } else {
            Vec::new()
        };
        let (m, wpos) = self
            .camera_from_world
            .unwrap_or((DMat4::IDENTITY, world_pos));
        let mut lens = lens;
        if let Some(d) = self.depth_of_field {
            // Camera-space lengths in world units: the camera's uniform scale is dropped below.
            let world_per_camera = self.world_per_camera_unit();
            let k = lens.len();
            paths.push((format!(".lens[{k}]"), d.pos));
            paths.push((format!(".lens[{k}].ThinLens.radius"), d.pos));
            paths.push((format!(".lens[{k}].ThinLens.focus_distance"), d.focus_pos));
            lens.push(LensDesc::ThinLens {
                radius: Some(d.radius * world_per_camera),
                fstop: None,
                focus_distance: d.focus * world_per_camera,
            });
        }
        paths.push((".placement".into(), wpos));
        paths.push((".placement.Matrix[0]".into(), wpos));
        let g = world_mirror(m);
        let flip = DMat4::from_scale(DVec3::new(1.0, 1.0, -1.0));
        let a = g * m.inverse() * flip;
        // Keep the rotation: a uniform scale of the camera does not change the image.
        let l = DMat3::from_mat4(a);
        let r = l * (1.0 / uniform_scale(l));
        let placement = DMat4::from_cols(
            r.x_axis.extend(0.0),
            r.y_axis.extend(0.0),
            r.z_axis.extend(0.0),
            a.w_axis,
        );
        let outputs = self
            .displays
            .iter()
            .enumerate()
            .map(|(i, d)| {
                paths.push((format!(".outputs[{i}]"), d.pos));
                paths.push((format!(".outputs[{i}].file"), d.pos));
                OutputDesc {
                    file: d.file.clone(),
                    format: None,
                    passes: Some(d.passes.clone()),
                    beauty_alpha: d.beauty_alpha,
                }
            })
            .collect();
        let ((gain, gamma), epos) = self.exposure.unwrap_or(((1.0, 1.0), world_pos));
        paths.push((".imager".into(), epos));
        paths.push((".imager.gain".into(), epos));
        paths.push((".imager.gamma".into(), epos));
        if let Some((_, p)) = self.background {
            paths.push((".imager.background".into(), p));
        }
        if let Some((_, p)) = self.pattern {
            paths.push((".imager.pattern".into(), p));
            paths.push((".imager.pattern.Disk".into(), p));
        }
        let imager = ImagerDesc {
            background: self.background.map(|b| b.0),
            gain,
            tone_map: ToneMapDesc::None,
            gamma: Some(gamma),
            pattern: self.pattern.map(|p| p.0),
        };
        (
            CameraDesc {
                name: "camera".into(),
                fov_y,
                resolution: (w, h),
                aspect: (self.screen.is_some() || pixel_aspect != 1.0).then_some(aspect),
                placement: PlacementDesc::Matrix(rows(placement)),
                outputs,
                imager: Some(imager),
                lens,
                atmosphere: None,
                space_scale: self.space_scale(),
            },
            paths,
        )
    }

    /// The world length of a camera-space unit: the inverse of the camera transformation's
    /// uniform scale (1 before `WorldBegin` or when it does not scale).
    pub fn world_per_camera_unit(&self) -> f64 {
        let m = self.camera_from_world.map_or(DMat4::IDENTITY, |c| c.0);
        1.0 / uniform_scale(DMat3::from_mat4(m))
    }

    /// The camera's `space_scale`: the camera-space length of one world unit, which the
    /// camera-space passes (`z`, `P`) are measured in; `None` when the camera
    /// transformation does not scale (a rotation rounded to a few digits does not:
    /// `camera_rotation::uniform_scale`).
    pub fn space_scale(&self) -> Option<f64> {
        let s = 1.0 / self.world_per_camera_unit();
        (s != 1.0).then_some(s)
    }

    /// `samples` of the options.
    pub fn samples(&self) -> SamplesDesc {
        SamplesDesc::Fixed(self.samples.map_or(4, |s| s.0))
    }

    /// `filter` of the options.
    pub fn filter(&self) -> FilterDesc {
        self.filter.map_or(
            FilterDesc::Gaussian {
                sigma: 0.5,
                radius: 1.0,
            },
            |f| f.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p() -> Pos {
        Pos::default()
    }

    #[test]
    fn default_camera_looks_down_rib_plus_z() {
        let (c, _) = CameraOptions::default().camera(p());
        assert_eq!(c.resolution, (640, 480));
        assert!((c.fov_y - 90.0).abs() < 1e-12);
        let PlacementDesc::Matrix(m) = c.placement else {
            panic!("a matrix")
        };
        // Identity: the world is mirrored instead, so the camera is the identity.
        assert_eq!(m, rows(DMat4::IDENTITY));
    }

    #[test]
    fn fov_spans_the_shorter_side() {
        let o = CameraOptions {
            format: Some(((100, 200, 1.0), p())),
            fov: Some((90.0, p())),
            ..Default::default()
        };
        let (c, _) = o.camera(p());
        // Portrait: 90° across the width, so tan(fov_y/2) = 2.
        assert!(
            (c.fov_y - 2.0 * 2f64.atan().to_degrees()).abs() < 1e-12,
            "{}",
            c.fov_y
        );
        assert_eq!(c.aspect, None);
    }

    #[test]
    fn camera_translation_moves_the_eye() {
        // `Translate 0 0 5` before WorldBegin: the world is 5 units in front of the camera,
        // so the eye sits at RIB world z = −5, our z = +5.
        let o = CameraOptions {
            camera_from_world: Some((DMat4::from_translation(DVec3::new(0.0, 0.0, 5.0)), p())),
            ..Default::default()
        };
        let (c, _) = o.camera(p());
        let PlacementDesc::Matrix(m) = c.placement else {
            panic!("a matrix")
        };
        assert_eq!(m[2][3], 5.0);
        assert_eq!(m[0][0], 1.0);
        assert_eq!(m[2][2], 1.0);
    }
}
