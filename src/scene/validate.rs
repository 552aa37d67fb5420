//! Merging the loaded files into one list per element kind, and checking every value:
//! finite numbers, ranges, output formats. Each element that passes is converted to the
//! component data it will carry ([`Camera`], [`Emitter`], [`Material`], [`RenderSettings`]).

use std::path::{Path, PathBuf};

use glam::{DAffine3, DMat3, DVec3};

use super::camera_rotation::snapped_rotation;
pub use super::checker::{Checker, Item};
use super::desc::{
    BvhQualityDesc, CameraDesc, DiagnosticDesc, FaceDesc, FeatureDesc, FilterDesc, FormatDesc,
    GroupDesc, InstanceDesc, IntegratorDesc, LightDesc, LightKindDesc, MaterialDesc, ObjectDesc,
    OptionsDesc, OutputDesc, PassDesc, PhotonFilterDesc, PhotonMapDesc, PlacementDesc,
    ProgressiveDesc, RenderDesc, SceneDesc,
};
use super::diagnostics::Sources;
use super::syntax::{Helps, Syntax};
use crate::components::{Camera, Emitter, ImageFormat, LightShape, Material, OutputSpec, Pass};
use crate::features::{Feature, Features};
use crate::settings::{
    BvhQuality, Face, Integrator, PhotonFilter, PhotonMapFile, PhotonMapSettings, PhotonSettings,
    PixelFilter, ProgressiveSettings, RenderSettings,
};

pub use crate::settings::MAX_FILTER_RADIUS;

/// Most progressive photon passes of one map (every pass is kept in memory).
pub const MAX_PASSES: u32 = 65536;

/// All files' elements, in load order.
#[derive(Debug, Default)]
pub struct Merged<'a> {
    /// The single `options` entry, if any.
    pub options: Option<Item<'a, OptionsDesc>>,
    /// The single `render` entry, if any.
    pub render: Option<Item<'a, RenderDesc>>,
    /// Cameras.
    pub cameras: Vec<Item<'a, CameraDesc>>,
    /// Lights.
    pub lights: Vec<Item<'a, LightDesc>>,
    /// Materials.
    pub materials: Vec<Item<'a, MaterialDesc>>,
    /// Objects.
    pub objects: Vec<Item<'a, ObjectDesc>>,
    /// Instances.
    pub instances: Vec<Item<'a, InstanceDesc>>,
    /// Groups.
    pub groups: Vec<Item<'a, GroupDesc>>,
    /// Phenomena (named shader graphs).
    pub phenomena: Vec<Item<'a, super::desc::PhenomenonDesc>>,
}

fn items<'a, T>(src: &Sources, file: usize, kind: &str, list: &'a [T]) -> Vec<Item<'a, T>> {
    list.iter()
        .enumerate()
        .map(|(i, desc)| Item::new(src, file, format!("{kind}[{i}]"), desc))
        .collect()
}

/// Merges the parsed files; a second `options` or `render` entry is an error.
pub fn merge<'a>(src: &mut Sources, scenes: &'a [Option<SceneDesc>]) -> Merged<'a> {
    let mut m = Merged::default();
    for (file, scene) in scenes.iter().enumerate() {
        let Some(scene) = scene else { continue };
        if let Some(options) = &scene.options {
            match &m.options {
                Some(first) => {
                    let help = format!("first defined at {}", first.pos);
                    src.error(file, "options", "options are given twice", Some(help));
                }
                None => m.options = Some(Item::new(src, file, "options".into(), options)),
            }
        }
        if let Some(render) = &scene.render {
            match &m.render {
                Some(first) => {
                    let help = format!("first defined at {}", first.pos);
                    src.error(file, "render", "render entry is given twice", Some(help));
                }
                None => m.render = Some(Item::new(src, file, "render".into(), render)),
            }
        }
        m.cameras
            .extend(items(src, file, "cameras", &scene.cameras));
        m.lights.extend(items(src, file, "lights", &scene.lights));
        m.materials
            .extend(items(src, file, "materials", &scene.materials));
        m.objects
            .extend(items(src, file, "objects", &scene.objects));
        m.instances
            .extend(items(src, file, "instances", &scene.instances));
        m.groups.extend(items(src, file, "groups", &scene.groups));
        m.phenomena
            .extend(items(src, file, "phenomena", &scene.phenomena));
    }
    if m.render.is_none() && !scenes.is_empty() {
        src.error(
            0,
            "",
            "the scene has no render entry",
            Some("add `render: (root: \"<group>\", camera: \"<camera>\")`".into()),
        );
    }
    m
}

/// Render settings from `options` (defaults when absent).
pub fn settings(src: &mut Sources, options: Option<&Item<'_, OptionsDesc>>) -> RenderSettings {
    let Some(item) = options else {
        return RenderSettings::default();
    };
    let o = item.desc;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let (spp, adaptive) = super::samples::samples(&mut ck, &item.at(".samples"), o.samples);
    let integrator = match o.integrator {
        IntegratorDesc::Direct => Integrator::Direct,
        IntegratorDesc::Path => Integrator::Path,
    };
    if o.max_depth == 0 {
        ck.error(
            &item.at(".max_depth"),
            "max_depth must be at least 1, found 0",
        );
    }
    if o.light_samples == 0 {
        ck.error(
            &item.at(".light_samples"),
            "light_samples must be at least 1, found 0",
        );
    }
    let filter = match o.filter {
        FilterDesc::Box => PixelFilter::Box,
        FilterDesc::Gaussian { sigma, radius } => {
            for (name, x) in [("sigma", sigma), ("radius", radius)] {
                let path = item.at(&format!(".filter.Gaussian.{name}"));
                if ck.finite(&path, name, x) && x <= 0.0 {
                    ck.error(&path, format!("{name} must be positive, found {x}"));
                } else if name == "radius" && x > MAX_FILTER_RADIUS {
                    // Samples that far from their pixel leave the image: a black frame.
                    ck.error(
                        &path,
                        format!("radius must be at most {MAX_FILTER_RADIUS} pixels, found {x}"),
                    );
                }
            }
            PixelFilter::Gaussian {
                sigma: sigma as f32,
                radius: radius as f32,
            }
        }
    };
    let mut map = |name: &str, d: Option<&PhotonMapDesc>| {
        d.map(|d| photon_map(&mut ck, &item.at(&format!(".{name}")), d))
    };
    let photons = PhotonSettings {
        caustics: map("caustics", o.caustics.as_ref()),
        global_illumination: map("global_illumination", o.global_illumination.as_ref()),
        depth: o.photon_depth.map(|d| d.depth()).unwrap_or_default(),
    };
    let photon_map = o.photon_map.as_ref().map(|f| {
        if f.file.trim().is_empty() {
            ck.error(
                &item.at(".photon_map.file"),
                "photon_map file is empty: name the file the photon maps are kept in, e.g. \"scene.pmap\"",
            );
        }
        PhotonMapFile {
            path: PathBuf::from(&f.file),
            rebuild: f.rebuild,
        }
    });
    let settings = RenderSettings {
        photons,
        photon_map,
        spp,
        adaptive,
        filter,
        seed: o.seed,
        max_depth: o.max_depth,
        reflection_depth: o.reflection_depth,
        refraction_depth: o.refraction_depth,
        light_samples: o.light_samples.max(1),
        integrator,
        face: match o.face {
            FaceDesc::Front => Face::Front,
            FaceDesc::Both => Face::Both,
            FaceDesc::Cull => Face::Cull,
        },
        bvh_quality: match o.bvh_quality {
            BvhQualityDesc::Fast => BvhQuality::Fast,
            BvhQualityDesc::Medium => BvhQuality::Medium,
            BvhQualityDesc::High => BvhQuality::High,
        },
        disabled: switched_off(&o.disable),
        diagnostic: o.diagnostic.map(|d| diagnostic(&mut ck, item, d)),
    };
    unmet_diagnostic(&mut ck, item, &settings);
    settings
}

/// Refuses, at the options' `diagnostic`, a photon view the scene's own options cannot draw
/// (`crate::diagnostic_needs`), with the help written in the scene's syntax: `check` refuses
/// what `render` would.
fn unmet_diagnostic(ck: &mut Checker<'_>, item: &Item<'_, OptionsDesc>, settings: &RenderSettings) {
    use crate::diagnostic_needs::{unmet, Unmet};
    let Some(unmet) = unmet(settings) else {
        return;
    };
    let syntax = ck.src.syntax(ck.file);
    let help = match unmet {
        Unmet::NoPhotonMaps => syntax.help(
            "turn on `caustics: (…)` or `global_illumination: (…)` in the scene's options",
            "add `caustic on` or `globillum on` to the options block",
        ),
        Unmet::PathIntegrator => syntax.help(
            "set `integrator: Direct` in the scene's options",
            "the photon view needs the Direct integrator",
        ),
    };
    ck.src
        .error(ck.file, &item.at(".diagnostic"), unmet.reason(), Some(help));
}

/// The diagnostic `d` asks for; a size or maximum that is not a number > 0 is an error.
fn diagnostic(
    ck: &mut Checker<'_>,
    item: &Item<'_, OptionsDesc>,
    d: DiagnosticDesc,
) -> crate::diagnostic::Diagnostic {
    use crate::diagnostic::Diagnostic;
    let mut positive = |path: &str, name: &str, x: f64| {
        let path = item.at(path);
        if ck.finite(&path, name, x) && x <= 0.0 {
            ck.error(&path, format!("{name} must be positive, found {x}"));
        }
        x as f32
    };
    match d {
        DiagnosticDesc::Samples => Diagnostic::Samples,
        DiagnosticDesc::Grid { space, size } => Diagnostic::Grid {
            space: space.space(),
            size: positive(".diagnostic.Grid.size", "size", size),
        },
        DiagnosticDesc::Photon { quantity, max } => Diagnostic::Photon {
            quantity: quantity.quantity(),
            max: positive(".diagnostic.Photon.max", "max", max),
        },
        DiagnosticDesc::Bvh { quantity, max } => {
            if max == Some(0) {
                ck.error(
                    &item.at(".diagnostic.Bvh.max"),
                    "max must be positive, found 0",
                );
            }
            Diagnostic::Bvh {
                quantity: quantity.quantity(),
                max,
            }
        }
    }
}

/// The set that `options.disable` lists.
fn switched_off(list: &[FeatureDesc]) -> Features {
    let mut set = Features::NONE;
    for d in list {
        set.insert(match d {
            FeatureDesc::Lens => Feature::Lens,
            FeatureDesc::Volume => Feature::Volume,
            FeatureDesc::Geometry => Feature::Geometry,
            FeatureDesc::Displacement => Feature::Displacement,
            FeatureDesc::Output => Feature::Output,
        });
    }
    set
}

/// Checks one photon map's knobs (`path` is the map's field in `options`).
fn photon_map(ck: &mut Checker<'_>, path: &str, d: &PhotonMapDesc) -> PhotonMapSettings {
    other_maps_fields(ck, path, d);
    if d.photons == 0 {
        ck.error(
            &format!("{path}.photons"),
            "photons must be at least 1, found 0",
        );
    }
    if d.gather < 2 {
        ck.error(
            &format!("{path}.gather"),
            format!(
                "gather must be at least 2 (the estimate divides by k − 1), found {}",
                d.gather
            ),
        );
    }
    if d.final_gather == 0 {
        ck.error(
            &format!("{path}.final_gather"),
            "final_gather must be at least 1, found 0",
        );
    }
    let radius = ck
        .non_negative(&format!("{path}.radius"), "radius", d.radius)
        .unwrap_or(0.0);
    let filter = match d.filter {
        PhotonFilterDesc::Box => PhotonFilter::Box,
        PhotonFilterDesc::Gauss => PhotonFilter::Gauss,
        PhotonFilterDesc::Cone { k } => {
            if !(k.is_finite() && (1.0..=1e6).contains(&k)) {
                ck.error(
                    &format!("{path}.filter.Cone.k"),
                    format!("cone filter k must be between 1 and 1e6, found {k}"),
                );
            }
            PhotonFilter::Cone {
                k: k.clamp(1.0, 1e6) as f32,
            }
        }
    };
    PhotonMapSettings {
        photons: d.photons.max(1),
        radius: radius as f32,
        gather: d.gather.max(2),
        final_gather: d.final_gather.max(1),
        precompute: d.precompute,
        aim: d.aim,
        filter,
        progressive: d.progressive.map(|p| progressive(ck, path, &p)),
    }
}

/// Warns about a field set away from its default on the map it does nothing for:
/// `final_gather` and `precompute` belong to `global_illumination`, `aim` to `caustics`.
fn other_maps_fields(ck: &mut Checker<'_>, path: &str, d: &PhotonMapDesc) {
    let default = PhotonMapDesc::default();
    let caustics = path.ends_with(".caustics");
    let misplaced: &[(&str, bool, &str)] = if caustics {
        &[
            (
                "final_gather",
                d.final_gather != default.final_gather,
                "global_illumination",
            ),
            (
                "precompute",
                d.precompute != default.precompute,
                "global_illumination",
            ),
        ]
    } else {
        &[("aim", d.aim != default.aim, "caustics")]
    };
    let this = if caustics {
        "caustics"
    } else {
        "global_illumination"
    };
    for &(field, set, owner) in misplaced {
        if set {
            ck.warn(
                &format!("{path}.{field}"),
                format!("{field} has no effect on the {this} map: it is a setting of {owner}"),
                &format!("move it into `{owner}: (…)`, or remove it"),
            );
        }
    }
}

/// Checks a photon map's `progressive: (passes, alpha)`.
fn progressive(ck: &mut Checker<'_>, path: &str, d: &ProgressiveDesc) -> ProgressiveSettings {
    if !(1..=MAX_PASSES).contains(&d.passes) {
        ck.error(
            &format!("{path}.progressive.passes"),
            format!(
                "passes must be between 1 and {MAX_PASSES}, found {}",
                d.passes
            ),
        );
    }
    if !(d.alpha > 0.0 && d.alpha <= 1.0) {
        ck.error(
            &format!("{path}.progressive.alpha"),
            format!(
                "alpha must be in (0, 1] (1: the radius never shrinks), found {}",
                d.alpha
            ),
        );
    }
    ProgressiveSettings {
        passes: d.passes.clamp(1, MAX_PASSES),
        alpha: if d.alpha > 0.0 && d.alpha <= 1.0 {
            d.alpha as f32
        } else {
            0.7
        },
    }
}

/// Checks a camera and builds its component.
pub fn camera(src: &mut Sources, item: &Item<'_, CameraDesc>) -> Option<Camera> {
    let c = item.desc;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let mut ok = true;
    let fov_path = item.at(".fov_y");
    // A `.mi` camera writes no field of view: its `aperture`, `focal` and `aspect` make it.
    let fov = match ck.src.syntax(ck.file) {
        Syntax::Mi => "the vertical field of view 2·atan(aperture / (2·focal·aspect))",
        _ => "fov_y",
    };
    if ck.finite(&fov_path, fov, c.fov_y) && !(c.fov_y > 0.0 && c.fov_y < 180.0) {
        let wide = if c.fov_y >= 180.0 {
            "; a view of 180° or more needs a fisheye lens, `lens: [Fisheye(fov: 180)]`"
        } else {
            ""
        };
        ck.src.error(
            ck.file,
            &fov_path,
            format!(
                "{fov} must be between 0 and 180 degrees (exclusive), found {}",
                c.fov_y
            ),
            Some(ck.src.syntax(ck.file).help_each(Helps {
                ron: &format!(
                    "fov_y is the full vertical angle of the view in degrees, such as 40 (a \
                     normal lens) or 90 (a wide one){wide}"
                ),
                mi: "the camera's `aperture`, `focal` and `aspect` give the view's vertical \
                     angle: with `aspect` and `focal` above 0 and an `aperture` of a few times \
                     `focal` or less it lies well below 180 degrees",
                rib: "the Projection's \"fov\" is the view's angle in degrees, such as 40 (a \
                      normal lens) or 90 (a wide one)",
                gltf: "a glTF camera's `yfov` is the vertical angle in radians, between 0 and π",
            })),
        );
        ok = false;
    }
    ok &= c.fov_y.is_finite();
    for (k, (what, n)) in [("width", c.resolution.0), ("height", c.resolution.1)]
        .into_iter()
        .enumerate()
    {
        if n == 0 {
            let help = ck.src.syntax(ck.file).help(
                "the image is width × height pixels, each at least 1: `resolution: (640, 480)`",
                "the image is width × height pixels, each at least 1: `resolution 640 480`",
            );
            ck.src.error(
                ck.file,
                &item.at(&format!(".resolution[{k}]")),
                format!("resolution {what} must be at least 1, found 0"),
                Some(help),
            );
            ok = false;
        }
    }
    let aspect = match c.aspect {
        Some(a) => {
            let path = item.at(".aspect");
            if ck.finite(&path, "aspect", a) && a <= 0.0 {
                ck.error(&path, format!("aspect must be positive, found {a}"));
            }
            ok &= a.is_finite() && a > 0.0;
            a
        }
        None => f64::from(c.resolution.0) / f64::from(c.resolution.1.max(1)),
    };
    let space_scale = match c.space_scale {
        Some(k) => {
            let path = item.at(".space_scale");
            if ck.finite(&path, "space_scale", k) && !(k > 0.0 && (k as f32).is_normal()) {
                ck.error(
                    &path,
                    format!("space_scale must be positive (the camera-space length of one world unit), found {k}"),
                );
            }
            ok &= k > 0.0 && (k as f32).is_normal();
            k as f32
        }
        None => 1.0,
    };
    let placement = placement(&mut ck, &item.at(".placement"), &c.placement);
    let mut outputs = Vec::new();
    for (k, o) in c.outputs.iter().enumerate() {
        match output(&mut ck, &item.at(&format!(".outputs[{k}]")), o) {
            Some(spec) => outputs.push(spec),
            None => ok = false,
        }
    }
    let world_from_camera = placement?;
    ok.then(|| Camera {
        world_from_camera: glam::Affine3A::from_mat3_translation(
            world_from_camera.matrix3.as_mat3(),
            world_from_camera.translation.as_vec3(),
        ),
        fov_y: c.fov_y.to_radians() as f32,
        width: c.resolution.0,
        height: c.resolution.1,
        aspect: aspect as f32,
        outputs,
        space_scale,
    })
}

/// The help for an `up` parallel to the view direction `forward` (a unit vector): an axis
/// far from it.
fn up_help(forward: DVec3) -> String {
    let axes = [
        (DVec3::Y, "(0, 1, 0)"),
        (DVec3::Z, "(0, 0, 1)"),
        (DVec3::X, "(1, 0, 0)"),
    ];
    let far = axes
        .iter()
        .find(|(a, _)| a.dot(forward).abs() < 0.9)
        .map_or("(0, 1, 0)", |(_, text)| text);
    format!(
        "up is the direction that is up in the image; it must lean away from the line from eye \
         to target: `up: {far}` does for this view"
    )
}

fn placement(ck: &mut Checker<'_>, path: &str, p: &PlacementDesc) -> Option<DAffine3> {
    match p {
        PlacementDesc::LookAt { eye, target, up } => {
            let eye_v = ck.v3(&format!("{path}.LookAt.eye"), "eye", *eye);
            let target_v = ck.v3(&format!("{path}.LookAt.target"), "target", *target);
            let up_v = ck.v3(&format!("{path}.LookAt.up"), "up", *up);
            let (eye, target, up) = (eye_v?, target_v?, up_v?);
            let forward = (target - eye).normalize_or_zero();
            if forward == DVec3::ZERO {
                ck.src.error(
                    ck.file,
                    &format!("{path}.LookAt.target"),
                    "target must differ from eye",
                    Some(
                        "the camera at eye looks toward target: make target the point to look \
                         at, such as the middle of the scene"
                            .into(),
                    ),
                );
                return None;
            }
            let z = -forward;
            let x = up.cross(z).normalize_or_zero();
            if x == DVec3::ZERO || up.length() < 1e-12 {
                ck.src.error(
                    ck.file,
                    &format!("{path}.LookAt.up"),
                    "up must not be zero or parallel to the view direction",
                    Some(up_help(forward)),
                );
                return None;
            }
            let y = z.cross(x);
            Some(DAffine3::from_mat3_translation(
                DMat3::from_cols(x, y, z),
                eye,
            ))
        }
        PlacementDesc::Matrix(m) => {
            let mpath = format!("{path}.Matrix[0]");
            let a = ck.affine(&mpath, "camera matrix", m)?;
            // A rotation rounded to a few digits is the rotation it rounds.
            let Some(rotation) = snapped_rotation(a.matrix3) else {
                let neutral = "a camera is placed by a rotation and a translation only: its \
                               axes must be at right angles and not mirrored";
                let help = ck.src.syntax(ck.file).help_each(Helps {
                    ron: "the 3×3 part must be a rotation (columns of length 1 at right angles, \
                          determinant 1): scale the objects instead, or place the camera with \
                          `LookAt(eye: …, target: …, up: …)`",
                    mi: "a camera instance's transform may rotate, move and scale evenly, but \
                         not shear, stretch unevenly or mirror: scale the objects' instances \
                         instead",
                    rib: neutral,
                    gltf: neutral,
                });
                ck.src.error(
                    ck.file,
                    &mpath,
                    "a camera matrix must be rigid: orthonormal rotation with determinant 1, \
                     no scale, shear or mirroring",
                    Some(help),
                );
                return None;
            };
            Some(DAffine3::from_mat3_translation(rotation, a.translation))
        }
    }
}

fn output(ck: &mut Checker<'_>, path: &str, o: &OutputDesc) -> Option<OutputSpec> {
    let ext = Path::new(&o.file)
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match (o.format, ext.as_deref()) {
        (Some(FormatDesc::Png), _) => ImageFormat::Png,
        (Some(FormatDesc::Exr), _) => ImageFormat::Exr,
        (Some(FormatDesc::Svg), _) => ImageFormat::Svg,
        (Some(FormatDesc::Eps), _) => ImageFormat::Eps,
        (None, Some("png")) => ImageFormat::Png,
        (None, Some("exr")) => ImageFormat::Exr,
        (None, Some("svg")) => ImageFormat::Svg,
        (None, Some("eps")) => ImageFormat::Eps,
        (None, other) => {
            ck.src.error(
                ck.file,
                &format!("{path}.file"),
                match other {
                    Some(e) => format!("unknown output extension \".{e}\" in \"{}\"", o.file),
                    None => format!("output file \"{}\" has no extension", o.file),
                },
                Some(
                    "use .png, .exr, .svg or .eps, or give `format: Png`, `Exr`, `Svg` or `Eps`"
                        .into(),
                ),
            );
            return None;
        }
    };
    if matches!(format, ImageFormat::Svg | ImageFormat::Eps) {
        return super::contours::vector_output(ck, path, o, format);
    }
    let descs = o.passes.clone().unwrap_or_else(|| vec![PassDesc::Beauty]);
    if descs.is_empty() {
        let neutral = "list the passes the output writes, such as Beauty";
        let help = ck.src.syntax(ck.file).help_each(Helps {
            ron: "leave out `passes` to write the Beauty pass, or list the passes to write, \
                  such as `passes: [Beauty, Alpha]`",
            mi: neutral,
            rib: neutral,
            gltf: neutral,
        });
        ck.src.error(
            ck.file,
            &format!("{path}.passes"),
            "an output needs at least one pass",
            Some(help),
        );
        return None;
    }
    let mut passes: Vec<Pass> = Vec::new();
    let mut ok = true;
    for (k, p) in descs.iter().enumerate() {
        let pass = match p {
            PassDesc::Beauty => Pass::Beauty,
            PassDesc::Alpha => Pass::Alpha,
            PassDesc::Depth => Pass::Depth,
            PassDesc::Normal => Pass::Normal,
            PassDesc::CameraDepth => Pass::CameraDepth,
            PassDesc::CameraNormal => Pass::CameraNormal,
            PassDesc::CameraPosition => Pass::CameraPosition,
            PassDesc::ObjectId => Pass::ObjectId,
            PassDesc::MaterialId => Pass::MaterialId,
            PassDesc::Contours => Pass::Contours,
            PassDesc::Emission => Pass::Emission,
            PassDesc::DiffuseDirect => Pass::DiffuseDirect,
            PassDesc::DiffuseIndirect => Pass::DiffuseIndirect,
            PassDesc::Specular => Pass::Specular,
            PassDesc::Transmission => Pass::Transmission,
            PassDesc::Volume => Pass::Volume,
        };
        let ppath = format!("{path}.passes[{k}]");
        if format == ImageFormat::Png
            && (matches!(
                pass,
                Pass::Depth | Pass::Normal | Pass::ObjectId | Pass::MaterialId
            ) || pass.component().is_some()
                || Pass::CAMERA_SPACE.contains(&pass))
        {
            ck.src.error(
                ck.file,
                &ppath,
                format!("a PNG output cannot hold the {pass:?} pass"),
                Some(format!("write the {pass:?} pass to an .exr output")),
            );
            ok = false;
        } else if passes.contains(&pass) {
            ck.src.error(
                ck.file,
                &ppath,
                format!("pass {pass:?} is listed twice"),
                Some(format!(
                    "an output writes each pass once: remove this {pass:?}"
                )),
            );
            ok = false;
        } else if let Some((other, channels)) =
            pass.same_channels_as().filter(|(o, _)| passes.contains(o))
        {
            ck.src.error(
                ck.file,
                &ppath,
                format!(
                    "the {other:?} and {pass:?} passes both write the EXR {channels}: one file \
                     cannot hold both"
                ),
                Some(format!("write the {pass:?} pass to another .exr output")),
            );
            ok = false;
        }
        passes.push(pass);
    }
    ok.then(|| OutputSpec {
        path: PathBuf::from(&o.file),
        format,
        passes,
        beauty_alpha: o.beauty_alpha.unwrap_or(true),
    })
}

/// Checks a light and builds its component.
pub fn light(src: &mut Sources, item: &Item<'_, LightDesc>) -> Option<Emitter> {
    let l = item.desc;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    let color_name = ck.src.syntax(ck.file).named("color", "color", "lightcolor");
    let color = ck.colour(&item.at(".color"), color_name, l.color);
    let intensity = ck.non_negative(&item.at(".intensity"), "intensity", l.intensity);
    let shadow_factor = ck
        .non_negative(&item.at(".shadow_factor"), "shadow_factor", l.shadow_factor)
        .and_then(|f| {
            if f > 1.0 {
                ck.error(
                    &item.at(".shadow_factor"),
                    format!("shadow_factor must be at most 1, found {f}"),
                );
                None
            } else {
                Some(f as f32)
            }
        });
    let kind = |s: &str| item.at(&format!(".kind.{s}"));
    let is_area = matches!(
        l.kind,
        LightKindDesc::Rect { .. }
            | LightKindDesc::Disc { .. }
            | LightKindDesc::Sphere { .. }
            | LightKindDesc::Cylinder { .. }
    );
    let samples = match (l.samples, is_area) {
        (None, true) => Some(16),
        (None, false) | (Some(1), false) => Some(1),
        (Some(0), _) => {
            ck.error(&item.at(".samples"), "samples must be at least 1, found 0");
            None
        }
        (Some(n), true) => Some(n),
        (Some(n), false) => {
            let what = match l.kind {
                LightKindDesc::Ambient => "an ambient",
                _ => "a delta",
            };
            ck.src.error(
                ck.file,
                &item.at(".samples"),
                format!("samples must be 1 for {what} light, found {n}"),
                Some("only area lights take several samples; remove `samples`".into()),
            );
            None
        }
    };
    let f32v = |v: DVec3| v.as_vec3();
    let shape = match &l.kind {
        LightKindDesc::Ambient => LightShape::Ambient,
        LightKindDesc::Point { position } => LightShape::Point {
            position: f32v(ck.v3(&kind("Point.position"), "position", *position)?),
        },
        LightKindDesc::Spot {
            position,
            target,
            cone_angle,
            penumbra,
            beam_distribution,
        } => {
            let p = ck.v3(&kind("Spot.position"), "position", *position);
            let t = ck.v3(&kind("Spot.target"), "target", *target);
            let mut ok = true;
            let cone_path = kind("Spot.cone_angle");
            if ck.finite(&cone_path, "cone_angle", *cone_angle)
                && !(*cone_angle > 0.0 && *cone_angle <= 90.0)
            {
                ck.src.error(
                    ck.file,
                    &cone_path,
                    format!("cone_angle must be in (0, 90] degrees, found {cone_angle}"),
                    Some(
                        "cone_angle is the angle in degrees from the spot's axis to the edge of \
                         its cone (90 lights a half space, a cone 180° across); a light that \
                         shines every way is a point light"
                            .into(),
                    ),
                );
                ok = false;
            }
            let pen_path = kind("Spot.penumbra");
            if ck.finite(&pen_path, "penumbra", *penumbra)
                && !(*penumbra >= 0.0 && *penumbra <= *cone_angle)
            {
                ck.error(
                    &pen_path,
                    format!(
                        "penumbra must be in [0, cone_angle] = [0, {cone_angle}] degrees, \
                         found {penumbra}"
                    ),
                );
                ok = false;
            }
            let syntax = ck.src.syntax(ck.file);
            let beam = ck.non_negative(
                &kind("Spot.beam_distribution"),
                syntax.named("beam_distribution", "beam_distribution", "beamdistribution"),
                *beam_distribution,
            );
            let (p, t, beam) = (p?, t?, beam?);
            let direction = (t - p).normalize_or_zero();
            if direction == DVec3::ZERO {
                // A `.mi` spot is aimed by its `direction`, a RIB one from `from` to `to`.
                let message = super::lights::aim_error(syntax, true);
                ck.error(&kind("Spot.target"), message);
                return None;
            }
            if !ok || !cone_angle.is_finite() || !penumbra.is_finite() {
                return None;
            }
            LightShape::Spot {
                position: f32v(p),
                direction: f32v(direction),
                cone_angle: cone_angle.to_radians() as f32,
                penumbra: penumbra.to_radians() as f32,
                beam_distribution: beam as f32,
            }
        }
        LightKindDesc::Directional { direction } => {
            let path = kind("Directional.direction");
            let d = ck.v3(&path, "direction", *direction)?.normalize_or_zero();
            if d == DVec3::ZERO {
                // A RIB `distantlight` shines from `from` to `to`.
                let message = super::lights::aim_error(ck.src.syntax(ck.file), false);
                ck.error(&path, message);
                return None;
            }
            LightShape::Directional { direction: f32v(d) }
        }
        LightKindDesc::Rect {
            corner,
            edge_u,
            edge_v,
        } => {
            let c = ck.v3(&kind("Rect.corner"), "corner", *corner);
            let u = ck.v3(&kind("Rect.edge_u"), "edge_u", *edge_u);
            let v = ck.v3(&kind("Rect.edge_v"), "edge_v", *edge_v);
            let (c, u, v) = (c?, u?, v?);
            if u.cross(v).length_squared() == 0.0 {
                let edges = ck.src.syntax(ck.file).named(
                    "edge_u and edge_v",
                    "the two edges of `rectangle`",
                    "edge_u and edge_v",
                );
                ck.error(
                    &kind("Rect.edge_v"),
                    format!("{edges} must span a non-zero area"),
                );
                return None;
            }
            LightShape::Rect {
                corner: f32v(c),
                edge_u: f32v(u),
                edge_v: f32v(v),
            }
        }
        other => super::lights::area_shape(&mut ck, &item.path, other)?,
    };
    let attenuation = super::lights::attenuation(&mut ck, item);
    let visible = super::lights::visible(&mut ck, item, is_area);
    let photons = super::lights::ambient_photons(&mut ck, item);
    photons?;
    // What makes the radiant value, named as the scene's format writes it.
    let radiant = super::lights::radiant_name(ck.src.syntax(ck.file));
    Some(Emitter {
        shape,
        radiant: ck
            .radiant(&item.at(".intensity"), radiant, color? * intensity?)?
            .as_vec3(),
        shadows: l.shadows,
        shadow_factor: shadow_factor?,
        samples: samples?,
        visible: visible?,
        attenuation: attenuation?,
        inverse_square: l.inverse_square,
    })
}

/// Checks a material and builds its component.
pub fn material(src: &mut Sources, item: &Item<'_, MaterialDesc>) -> Option<Material> {
    let m = item.desc;
    let mut ck = Checker {
        src,
        file: item.file,
    };
    // A RIB emission is an `AreaLightSource`'s `intensity` times its `lightcolor`.
    let what = ck.src.syntax(ck.file).named(
        "emission",
        "emission",
        "the area light's intensity × lightcolor",
    );
    let emission = ck
        .colour(&item.at(".emission"), what, m.emission)
        .and_then(|e| ck.radiant(&item.at(".emission"), what, e));
    let shader = super::shaders::shader(&mut ck, &item.at(".shader"), &m.shader);
    let shadow = super::material_shaders::shadow(&mut ck, &item.at(".shadow"), m.shadow.as_ref());
    let environment = super::material_shaders::environment(
        &mut ck,
        &item.at(".environment"),
        m.environment.as_ref(),
    );
    let photon = super::material_shaders::photon(&mut ck, &item.at(".photon"), m.photon.as_ref());
    Some(Material {
        shader: shader?,
        two_sided: m.two_sided,
        emission: emission?.as_vec3(),
        shadow: shadow.ok()?,
        environment: environment.ok()?,
        photon: photon.ok()?,
        ..Material::default()
    })
}

/// The built-in material used where neither an instance nor its object names one.
pub fn default_material() -> Material {
    Material::default()
}
