//! The scene-element blocks other than geometry: `options`, `camera`, `light`, `material`,
//! `declare` (`phenomenon` with its `shader`s and `root`; native `shader` declarations are
//! skipped) and top-level named `shader`s.
//!
//! Statements that are read but not mapped give located warnings. Light `energy`, `caustic
//! photons` and `globillum photons` become the light's photon controls; the photon options
//! and `photonmap file` map onto the photon maps (`photon_options.rs`); material `photon`
//! shaders are read and reported "read but not yet mapped".

use super::super::located::{Pos, Problem};
use super::cursor::Cursor;
use super::incremental;
use super::lexer::{Tok, Token};
use super::model::{AreaShape, RawCamera, RawLight, RawMaterial, RawOptions, Space};
use super::photon_options::PhotonOptions;
use super::shaders;
use super::statements::Reader;
use super::switches;
use super::unmapped_options;
use crate::scene::desc::{
    FaceDesc, FormatDesc, MaterialDesc, OptionsDesc, OutputDesc, PassDesc, SamplesDesc,
};
use crate::scene::suggest::closest;

fn name_of(c: &mut Cursor, what: &str) -> Option<(String, Pos)> {
    c.string(&format!("the name of the {what}"))
}

/// Reports the word at the cursor as not part of `block`, with a suggestion from `known`,
/// then skips it and its arguments.
fn unknown(c: &mut Cursor, block: &str, known: &[&str]) {
    let Some(t) = c.advance() else { return };
    let shown = match &t.tok {
        Tok::Num(_) => "number".to_string(),
        Tok::Str(s) => format!("string \"{s}\""),
        other => other.describe(),
    };
    let mut p = Problem::error(t.pos, format!("unexpected {shown} in {block}"));
    if let Tok::Word(w) = &t.tok {
        if let Some(s) = closest(w, known.iter().copied()) {
            p = p.with_help(format!("did you mean \"{s}\"?"));
        }
    } else {
        p = p.with_help(format!(
            "expected a {block} statement (a word such as \"{}\") or \"end {block}\"",
            known[0]
        ));
    }
    c.report(p);
    c.skip_arguments();
}

const OPTIONS: &[&str] = &[
    "samples",
    "contrast",
    "trace",
    "face",
    "shadow",
    "object",
    "camera",
    "caustic",
    "globillum",
    "finalgather",
    "photonmap",
    "photon",
    "diagnostic",
    "contour",
    "lens",
    "volume",
    "geometry",
    "displace",
    "output",
    "end",
];

/// Whether `photon` is the physics library's photon shader of the material shader
/// `material` (`dgs_material_photon` of `dgs_material`, `dielectric_material_photon` of
/// `dielectric_material`): it scatters photons as the material scatters light, which is what
/// the photon pass does with every material's BSDF, so it maps without a warning.
fn is_photon_twin(material: &str, photon: &str) -> bool {
    matches!(material, "dgs_material" | "dielectric_material")
        && photon.strip_suffix("_photon") == Some(material)
}

/// `options "name" … end options`.
pub fn options(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = name_of(c, "options") else {
        c.skip_to_end("options", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    let earlier = incremental::earlier_body(r, "options");
    let mut o = RawOptions {
        at: c.located(open),
        // mental ray's default is `face both` (seed 000: "The default is face both"); the
        // RON default is one-sided.
        desc: OptionsDesc {
            face: FaceDesc::Both,
            ..OptionsDesc::default()
        },
        space: Space::Camera,
        shadows: true,
        values: Default::default(),
    };
    let mut contrast = (0.1, 0.1, 0.1);
    let mut samples: Option<(i64, i64)> = None;
    let mut photons = PhotonOptions::default();
    // `trace off`: no reflection or refraction rays, whatever the trace depth says.
    let mut traced = true;
    let start = c.index();
    incremental::replay_statements(c, earlier.as_ref());
    loop {
        let Some(t) = c.block_token("options", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            unknown(c, "options", OPTIONS);
            continue;
        };
        if w == "end" {
            break;
        }
        c.advance();
        match w.as_str() {
            "samples" => {
                o.values.record(".samples", c.located(c.pos()));
                let Some(a) = c.number("samples") else {
                    continue;
                };
                let b = if c.at_number() {
                    c.number("samples").unwrap_or(a)
                } else {
                    a
                };
                samples = Some((a.round() as i64, b.round() as i64));
            }
            "contrast" => {
                let Some(v) = c.numbers(3, "contrast") else {
                    continue;
                };
                contrast = (v[0], v[1], v[2]);
                if c.at_number() {
                    c.advance();
                }
            }
            "trace" => {
                if c.eat_word("depth") {
                    let at = c.located(c.pos());
                    for path in [".reflection_depth", ".refraction_depth", ".max_depth"] {
                        o.values.record(path, at.clone());
                    }
                    let Some(a) = c.count("trace depth") else {
                        continue;
                    };
                    let b = if c.at_number() {
                        c.count("trace depth").unwrap_or(a)
                    } else {
                        a
                    };
                    let s = if c.at_number() {
                        c.count("trace depth").unwrap_or(a.saturating_add(b))
                    } else {
                        a.saturating_add(b)
                    };
                    // mental ray counts reflection and refraction rays (the camera ray
                    // is level 0) and shades the hit of every ray it traces: a path of
                    // `s` such rays ends at vertex `s + 1`, lit, and no budget exceeds
                    // the sum.
                    o.desc.reflection_depth = a.min(s);
                    o.desc.refraction_depth = b.min(s);
                    o.desc.max_depth = s.saturating_add(1);
                } else {
                    traced = c.switch();
                }
            }
            "face" => {
                if c.eat_word("both") {
                    o.desc.face = FaceDesc::Both;
                } else if c.eat_word("front") {
                    // Back faces left out of the rays, as mental ray does (seed 000).
                    o.desc.face = FaceDesc::Cull;
                } else if c.eat_word("back") {
                    c.warn(
                        t.pos,
                        "\"face back\" is not supported; front faces are rendered",
                    );
                } else {
                    face_error(c);
                }
            }
            "shadow" => {
                if c.at_word("sort") || c.at_word("segments") {
                    c.advance();
                } else {
                    o.shadows = c.switch();
                }
            }
            "object" | "camera" => {
                if c.eat_word("space") {
                    o.space = if w == "object" {
                        Space::Object
                    } else {
                        Space::Camera
                    };
                } else {
                    let p = c.pos();
                    c.error(p, format!("expected \"space\" after \"{w}\""));
                }
            }
            "caustic" => photons.caustic(c, t.pos),
            "globillum" => photons.globillum(c, t.pos),
            "finalgather" => photons.final_gather(c, t.pos),
            "diagnostic" => {
                switches::diagnostic(c, t.pos, &mut o.desc);
                o.values.record(".diagnostic", c.located(t.pos));
            }
            "contour" => super::contours::option(c, t.pos, &mut o.desc, &mut o.values),
            "photonmap" => photons.photon_map(c, t.pos),
            "photon" if c.at_word("trace") => photons.trace_depth(c),
            "photon" => {
                while c.at_word("file")
                    || c.at_word("trace")
                    || c.at_word("depth")
                    || c.at_word("rebuild")
                    || c.at_word("grid")
                    || c.at_word("photon")
                    || c.at_word("object")
                    || c.at_word("world")
                    || c.at_word("density")
                    || c.at_word("irradiance")
                    || c.at_word("accuracy")
                    || c.at_word("only")
                    || c.at_word("samples")
                {
                    c.advance();
                    c.skip_arguments();
                }
                c.skip_arguments();
                c.warn(t.pos, format!("\"{w}\" is read but not yet mapped"));
            }
            w if switches::is_switch(w) => switches::switch(c, w, &mut o.desc),
            w if unmapped_options::is_unmapped(w) => unmapped_options::read(c, w, t.pos),
            other => {
                let mut p = Problem::error(t.pos, format!("unknown option \"{other}\""));
                let known = OPTIONS.iter().copied().chain(unmapped_options::names());
                if let Some(s) = closest(other, known) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    let statements = c.record(start);
    c.expect_end("options", open);
    photons.apply(c, &mut o.desc, &mut o.values);
    if !traced {
        o.desc.reflection_depth = 0;
        o.desc.refraction_depth = 0;
    }
    if let Some((min, max)) = samples {
        // mental ray counts in powers of 4: `samples n` is 4ⁿ per pixel (below 0: one).
        let spp = |e: i64| 4u64.pow(e.clamp(0, 5) as u32);
        o.desc.samples = if max > min.max(0) {
            SamplesDesc::Adaptive {
                min: spp(min),
                max: spp(max),
                contrast,
            }
        } else {
            SamplesDesc::Fixed(spp(max))
        };
    }
    if fresh {
        incremental::keep(r, &name, "options", Default::default(), statements);
        r.raw.options.insert(name, o);
    }
}

/// `face` followed by something other than `front`, `back` or `both`: one error (with a
/// did-you-mean for a misspelt word, which is taken as the statement's argument).
fn face_error(c: &mut Cursor) {
    let (p, f) = (
        c.pos(),
        c.peek()
            .map_or("the end of the file".into(), |t| t.tok.describe()),
    );
    let mut problem = Problem::error(
        p,
        format!("expected front, back or both after face, found {f}"),
    );
    if let Some(Token {
        tok: Tok::Word(w), ..
    }) = c.peek()
    {
        if w != "end" {
            if let Some(s) = closest(w, ["front", "back", "both"]) {
                problem = problem.with_help(format!("did you mean \"{s}\"?"));
            }
            c.advance();
        }
    }
    c.report(problem);
}

const CAMERA: &[&str] = &[
    "frame",
    "output",
    "focal",
    "aperture",
    "aspect",
    "resolution",
    "environment",
    "lens",
    "volume",
    "clip",
    "offset",
    "window",
    "end",
];

/// `camera "name" … end camera`.
pub fn camera(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = name_of(c, "camera") else {
        c.skip_to_end("camera", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    let earlier = incremental::earlier_body(r, "camera");
    let (mut focal, mut aperture) = (1.0f64, 1.0f64);
    let mut cam = RawCamera {
        at: c.located(open),
        fov_y: 0.0,
        resolution: (768, 576),
        aspect: None,
        outputs: Vec::new(),
        environment: None,
        frame: 0.0,
        atmosphere: None,
        values: Default::default(),
    };
    // Where focal and aperture were written (the field of view is made of them).
    let (mut focal_at, mut aperture_at) = (None, None);
    let start = c.index();
    let replayed = incremental::replay_statements(c, earlier.as_ref());
    // Whether the incremental block's own `output` statements replaced the earlier list.
    let mut outputs_restated = false;
    loop {
        let Some(t) = c.block_token("camera", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            unknown(c, "camera", CAMERA);
            continue;
        };
        if w == "end" {
            break;
        }
        c.advance();
        match w.as_str() {
            "frame" => {
                if c.at_number() {
                    cam.frame = c.number("the frame number").unwrap_or(0.0);
                }
                c.skip_arguments();
            }
            "focal" => {
                if c.eat_word("infinity") {
                    c.warn(
                        t.pos,
                        "orthographic cameras (focal infinity) are not supported",
                    );
                } else {
                    let at = c.pos();
                    if let Some(v) = c.number("focal") {
                        focal = v;
                        focal_at = Some(at);
                    }
                }
            }
            "aperture" => {
                let at = c.pos();
                if let Some(v) = c.number("aperture") {
                    aperture = v;
                    aperture_at = Some(at);
                }
            }
            "aspect" => {
                cam.values.record(".aspect", c.located(c.pos()));
                cam.aspect = c.number("aspect");
            }
            "resolution" => {
                let width_at = c.located(c.pos());
                let Some(w) = c.count("resolution") else {
                    continue;
                };
                let height_at = c.located(c.pos());
                let Some(h) = c.count("resolution") else {
                    continue;
                };
                cam.resolution = (w, h);
                cam.values.record(".resolution[0]", width_at);
                cam.values.record(".resolution[1]", height_at);
            }
            "output" => {
                if c.index() > replayed && !outputs_restated {
                    // The outputs are one list: an incremental block that states any
                    // replaces the earlier ones.
                    cam.outputs.clear();
                    outputs_restated = true;
                }
                let before = cam.outputs.len();
                output(c, &mut cam.outputs);
                for k in before..cam.outputs.len() {
                    cam.values
                        .record(format!(".outputs[{k}]"), c.located(t.pos));
                }
            }
            "environment" => {
                if let Some(call) = c.shader_call_or_named("the environment shader", &r.raw.shaders)
                {
                    cam.environment = super::tutorial::environment(c, &call, &r.raw.linked)
                        .unwrap_or_else(|| shaders::environment(c, &call, &r.raw.shaders));
                }
            }
            "volume" => {
                if let Some(call) = c.shader_call_or_named("the volume shader", &r.raw.shaders) {
                    cam.values.record(".atmosphere", c.located(call.pos));
                    cam.atmosphere = super::volumes::volume(c, &call, "camera");
                }
            }
            "lens" => {
                if let Some(call) =
                    c.shader_call_or_named(&format!("the {w} shader"), &r.raw.shaders)
                {
                    c.warn(
                        call.pos,
                        format!("{w} shader \"{}\" is not mapped", call.name),
                    );
                }
            }
            "clip" | "offset" | "window" => {
                c.skip_arguments();
                c.warn(t.pos, format!("camera \"{w}\" is read but not mapped"));
            }
            other => {
                let mut p = Problem::error(t.pos, format!("unknown camera statement \"{other}\""));
                if let Some(s) = closest(other, CAMERA.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    let statements = c.record(start);
    c.expect_end("camera", open);
    if focal <= 0.0 || aperture <= 0.0 {
        let at = if focal <= 0.0 { focal_at } else { aperture_at };
        c.error(
            at.unwrap_or(open),
            format!(
                "camera \"{name}\" needs focal > 0 and aperture > 0, found {focal} and {aperture}"
            ),
        );
        return;
    }
    let aspect = cam
        .aspect
        .unwrap_or(f64::from(cam.resolution.0.max(1)) / f64::from(cam.resolution.1.max(1)));
    // The aperture is the film width; the film height is aperture / aspect.
    cam.fov_y = 2.0 * (aperture / (2.0 * focal * aspect)).atan().to_degrees();
    if let Some(at) = aperture_at.or(focal_at) {
        cam.values.record(".fov_y", c.located(at));
    }
    if fresh {
        incremental::keep(r, &name, "camera", Default::default(), statements);
        r.raw.cameras.insert(name, cam);
    }
}

/// `output ["type"] "format" [options…] "file"` (mental ray's form; the seed: "if you choose
/// rgb for the format and do not specify the optional parameters type and opt … the type
/// will default to rgba"). `output "type" "file"` with a data type that is no file format
/// (`"rgba" "x.png"`) is read too. Types: rgb → colour, rgba → colour and alpha, z → depth,
/// n → normals, tag → object ids, contour (`ps`/`eps`) → contour lines. The data type a format
/// gives by default: `zt` z, `nt` n, `tt` tag, `ps`/`eps` contour, every other rgba. PNG and
/// EXR are written; other formats go to a PNG (colour) or EXR (data) of the same stem, with a
/// warning; the format's options (numbers: quality, compression) are read and warned.
fn output(c: &mut Cursor, outputs: &mut Vec<OutputDesc>) {
    let Some((first, first_pos)) = c.string("the output type or format") else {
        return;
    };
    let mut strings = vec![(first, first_pos)];
    if c.at_string() {
        strings.extend(c.string("the output format or file"));
    }
    let mut options = None;
    while c.at_number() {
        let at = c.pos();
        let _ = c.number("an output option");
        options.get_or_insert(at);
    }
    if c.at_string() || options.is_some() {
        let Some(file) = c.string("the output file") else {
            return;
        };
        strings.push(file);
    }
    // (type, format, file)
    let (kind, format, (mut file, file_pos)) = match strings.as_slice() {
        [(t, tp), (f, fp), file] => (Some((t.clone(), *tp)), Some((f.clone(), *fp)), file.clone()),
        [(x, xp), file] if is_output_format(x) => (None, Some((x.clone(), *xp)), file.clone()),
        [(x, xp), file] => (Some((x.clone(), *xp)), None, file.clone()),
        [_] => {
            // Reports "expected a string for the output file, found …".
            let _ = c.string("the output file");
            return;
        }
        _ => return,
    };
    let contour = kind.as_ref().is_some_and(|k| k.0 == "contour");
    if let (Some((f, at)), false) = (&format, contour) {
        if !is_output_format(f) {
            let mut p = Problem::error(*at, format!("unknown output format \"{f}\""));
            p = match closest(f, OUTPUT_FORMATS.iter().copied()) {
                Some(s) => p.with_help(format!("did you mean \"{s}\"?")),
                None => p.with_help("stagelight writes \"png\" and \"exr\"; mental ray's other formats (\"rgb\", \"tif\", \"jpg\", …) become PNG or EXR files"),
            };
            c.report(p);
            return;
        }
    }
    if let Some(at) = options {
        let f = format.as_ref().map_or("", |f| f.0.as_str());
        c.warn(
            at,
            format!("the options of output format \"{f}\" are read and not used (stagelight writes PNG and EXR with their own settings)"),
        );
    }
    let format_name = format.as_ref().map(|f| f.0.as_str());
    let (kind, kind_pos) = kind.unwrap_or_else(|| {
        let t = match format_name {
            Some("zt") => "z",
            Some("nt") => "n",
            Some("tt") => "tag",
            Some("ps" | "eps") => "contour",
            _ => "rgba",
        };
        (t.to_string(), format.as_ref().map_or(file_pos, |f| f.1))
    });
    if kind == "contour" {
        // `output "contour" "ps"|"eps" "file"`: the contour lines as PostScript.
        match &format {
            Some((f, _)) if f == "ps" || f == "eps" => {}
            Some((f, at)) => {
                c.report(
                    Problem::error(
                        *at,
                        format!("contour output format \"{f}\" is not supported"),
                    )
                    .with_help("write \"ps\" or \"eps\" (Encapsulated PostScript)"),
                );
                return;
            }
            None => {}
        }
        outputs.push(OutputDesc {
            file,
            format: Some(FormatDesc::Eps),
            passes: Some(vec![PassDesc::Contours]),
            beauty_alpha: None,
        });
        return;
    }
    let passes = match kind.as_str() {
        "rgb" | "rgb_h" | "rgb_f" | "rgb_16" | "rgb_fp" => vec![PassDesc::Beauty],
        "rgba" | "rgba_h" | "rgba_f" | "rgba_16" | "rgba_fp" => {
            vec![PassDesc::Beauty, PassDesc::Alpha]
        }
        // mental ray's depth buffer: the camera-space Z of the frontmost object, a depth
        // along the view axis (not the distance along the ray).
        "z" => vec![PassDesc::CameraDepth],
        "n" => vec![PassDesc::Normal],
        "tag" => vec![PassDesc::ObjectId],
        other => {
            let mut p = Problem::error(
                kind_pos,
                format!("output type \"{other}\" is not supported"),
            );
            p = match format_name {
                Some(_) => p.with_help("expected \"rgb\", \"rgba\", \"z\", \"n\", \"tag\" or \"contour\""),
                None => p.with_help("expected \"rgb\", \"rgba\", \"z\", \"n\", \"tag\" or \"contour\", or a file format (\"png\", \"exr\", \"rgb\", \"tif\", …)"),
            };
            c.report(p);
            return;
        }
    };
    let colour = passes
        .iter()
        .all(|p| matches!(p, PassDesc::Beauty | PassDesc::Alpha));
    let deep = deeper_than_8_bits(&kind);
    let lower = file.to_ascii_lowercase();
    let format = if format_name == Some("png") && colour
        || format_name.is_none_or(|f| f != "exr") && lower.ends_with(".png") && colour
    {
        if let Some(depth) = deep {
            c.report(
                Problem::warning(
                    kind_pos,
                    format!("output type \"{kind}\" is {depth}, but \"{file}\" is written as an 8-bit PNG"),
                )
                .with_help("name an .exr file (or format \"exr\") to keep its precision"),
            );
        }
        FormatDesc::Png
    } else if format_name == Some("exr") || lower.ends_with(".exr") {
        FormatDesc::Exr
    } else {
        let stem = file
            .rsplit_once('.')
            .map_or(file.as_str(), |(s, _)| s)
            .to_string();
        // A type deeper than PNG's 8 bits keeps its precision in EXR, as data does.
        let (ext, format) = if colour && deep.is_none() {
            ("png", FormatDesc::Png)
        } else {
            ("exr", FormatDesc::Exr)
        };
        let new = format!("{stem}.{ext}");
        let what = match format_name {
            Some(f) => format!("stagelight writes PNG and EXR files, not format \"{f}\""),
            None => "stagelight writes PNG and EXR files".to_string(),
        };
        c.warn(
            file_pos,
            format!("output \"{file}\" is written as \"{new}\" ({what})"),
        );
        file = new;
        format
    };
    // The channels are those the type names: `rgb` writes no alpha (an EXR's `Beauty`
    // otherwise brings the coverage as `A`; a PNG writes it only with `Alpha`), `rgba` does.
    let beauty_alpha = (matches!(format, FormatDesc::Exr)
        && passes.contains(&PassDesc::Beauty)
        && !passes.contains(&PassDesc::Alpha))
    .then_some(false);
    outputs.push(OutputDesc {
        file,
        format: Some(format),
        passes: Some(passes),
        beauty_alpha,
    });
}

/// How an output type deeper than 8 bits per channel is described (`rgba_16`: "16 bits per
/// channel"; `_h`, `_f`, `_fp`: "floating point"); `None` for the 8-bit `rgb`/`rgba`.
fn deeper_than_8_bits(kind: &str) -> Option<&'static str> {
    if kind.ends_with("_16") {
        Some("16 bits per channel")
    } else if kind.ends_with("_h") || kind.ends_with("_f") || kind.ends_with("_fp") {
        Some("floating point")
    } else {
        None
    }
}

/// mental ray's image file formats (`output` statements).
const OUTPUT_FORMATS: &[&str] = &[
    "png", "exr", "rgb", "tif", "tifu", "tif3", "tif3u", "tif4", "tif4u", "tif16", "tif16u",
    "tif32", "tif32u", "tiff", "jpg", "jpeg", "pic", "picz", "alias", "rla", "rlb", "ppm",
    "qntpal", "qntntsc", "ct", "ctfp", "cth", "st", "vt", "wt", "zt", "nt", "tt", "bit", "cvt",
    "map", "hdr", "iff", "bmp", "tga", "psd", "ps", "eps",
];

fn is_output_format(s: &str) -> bool {
    OUTPUT_FORMATS.contains(&s)
}

const LIGHT: &[&str] = &[
    "origin",
    "direction",
    "spread",
    "rectangle",
    "disc",
    "sphere",
    "cylinder",
    "visible",
    "energy",
    "caustic",
    "globillum",
    "exponent",
    "shadowmap",
    "end",
];

fn vec3(c: &mut Cursor, what: &str) -> Option<(f64, f64, f64)> {
    c.numbers(3, what).map(|v| (v[0], v[1], v[2]))
}

fn samples(c: &mut Cursor) -> u32 {
    if !c.at_number() {
        return 16;
    }
    let u = c.count("area light samples").unwrap_or(4).max(1);
    let v = if c.at_number() {
        c.count("area light samples").unwrap_or(u).max(1)
    } else {
        u
    };
    c.skip_arguments();
    u.saturating_mul(v)
}

/// `light "name" "shader" (…) … end light`.
pub fn light(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = name_of(c, "light") else {
        c.skip_to_end("light", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    let earlier = incremental::earlier_body(r, "light");
    let Some((call, head)) =
        incremental::head_call(r, c, earlier.as_ref(), "the light shader", true)
    else {
        c.skip_to_end("light", open);
        return;
    };
    let mapped =
        super::tutorial::light(c, &call, &r.raw.linked).unwrap_or_else(|| shaders::light(c, &call));
    let mut values = super::value_positions::ValuePositions::default();
    super::param_paths::record(c, &call, None, &mut values);
    let mut origin = None;
    let mut direction = None;
    let mut spread = None;
    let mut area = None;
    let mut visible = false;
    let (mut energy, mut caustic_photons, mut globillum_photons) = (None, None, None);
    let start = c.index();
    incremental::replay_statements(c, earlier.as_ref());
    loop {
        let Some(t) = c.block_token("light", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            unknown(c, "light", LIGHT);
            continue;
        };
        if w == "end" {
            break;
        }
        c.advance();
        // Where the statement's values start, under each path they may become.
        let at = c.located(c.pos());
        for path in light_value_paths(w) {
            values.record(*path, at.clone());
        }
        match w.as_str() {
            "origin" => origin = vec3(c, "origin"),
            "direction" => direction = vec3(c, "direction"),
            "spread" => spread = c.number("spread"),
            "rectangle" => {
                let (Some(e), Some(f)) = (vec3(c, "rectangle"), vec3(c, "rectangle")) else {
                    continue;
                };
                area = Some((AreaShape::Rectangle(e, f), samples(c)));
            }
            "disc" => {
                let (Some(n), Some(radius)) = (vec3(c, "disc"), c.number("disc radius")) else {
                    continue;
                };
                area = Some((AreaShape::Disc(n, radius), samples(c)));
            }
            "sphere" => {
                let Some(radius) = c.number("sphere radius") else {
                    continue;
                };
                area = Some((AreaShape::Sphere(radius), samples(c)));
            }
            "cylinder" => {
                let (Some(a), Some(radius)) = (vec3(c, "cylinder"), c.number("cylinder radius"))
                else {
                    continue;
                };
                area = Some((AreaShape::Cylinder(a, radius), samples(c)));
            }
            "visible" => visible = c.switch(),
            "energy" => energy = vec3(c, "energy"),
            "exponent" | "shadowmap" => {
                c.skip_arguments();
                c.warn(t.pos, format!("light \"{w}\" is read but not yet mapped"));
            }
            "caustic" | "globillum" => {
                c.eat_word("photons");
                let n = c.count(&format!("{w} photons"));
                // mental ray's optional further numbers (store count, …) are not used.
                c.skip_arguments();
                if w == "caustic" {
                    caustic_photons = n;
                } else {
                    globillum_photons = n;
                }
            }
            other => {
                let mut p = Problem::error(t.pos, format!("unknown light statement \"{other}\""));
                if let Some(s) = closest(other, LIGHT.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    let statements = c.record(start);
    c.expect_end("light", open);
    let Some(m) = mapped else { return };
    if fresh {
        incremental::keep(r, &name, "light", head, statements);
        r.raw.lights.insert(
            name,
            RawLight {
                at: c.located(open),
                model: m.model,
                color: m.color,
                shadows: m.shadows,
                shadow_factor: m.shadow_factor,
                inverse_square: m.physical,
                attenuation: m.attenuation,
                origin,
                direction,
                spread,
                area,
                visible,
                energy,
                caustic_photons,
                globillum_photons,
                values,
            },
        );
    }
}

/// The description paths (below `lights[i]`) the values of light statement `w` may become.
fn light_value_paths(w: &str) -> &'static [&'static str] {
    match w {
        "origin" => &[".kind.Point.position", ".kind.Spot.position"],
        "direction" => &[".kind.Directional.direction", ".kind.Spot.target"],
        "spread" => &[".kind.Spot.cone_angle"],
        "rectangle" => &[".kind.Rect", ".samples"],
        "disc" => &[".kind.Disc", ".samples"],
        "sphere" => &[".kind.Sphere", ".samples"],
        "cylinder" => &[".kind.Cylinder", ".samples"],
        "energy" => &[".energy"],
        "caustic" => &[".caustic_photons"],
        "globillum" => &[".globillum_photons"],
        _ => &[],
    }
}

const MATERIAL: &[&str] = &[
    "opaque",
    "shadow",
    "photon",
    "volume",
    "environment",
    "displace",
    "contour",
    "end",
];

/// `material "name" [opaque] "shader" (…) [shadow|photon|volume|environment|displace|contour
/// "shader" (…)] end material`.
pub fn material(r: &mut Reader, c: &mut Cursor, open: Pos) {
    let Some((name, pos)) = name_of(c, "material") else {
        c.skip_to_end("material", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    let earlier = incremental::earlier_body(r, "material");
    c.eat_word("opaque");
    let Some((call, head)) =
        incremental::head_call(r, c, earlier.as_ref(), "the material shader", true)
    else {
        c.skip_to_end("material", open);
        return;
    };
    let mapped = super::tutorial::material(c, &call, &r.raw.linked)
        .unwrap_or_else(|| shaders::material(c, &call, &r.raw.shaders, &r.raw.textures, 0));
    let mut values = super::value_positions::ValuePositions::default();
    super::param_paths::record(c, &call, Some(".shader"), &mut values);
    let mut contour = None;
    let mut frame_fade = None;
    let mut interior = None;
    let mut displace = None;
    let (mut shadow, mut environment) = (None, None);
    let start = c.index();
    incremental::replay_statements(c, earlier.as_ref());
    loop {
        let Some(t) = c.block_token("material", open) else {
            return;
        };
        let Tok::Word(w) = &t.tok else {
            unknown(c, "material", MATERIAL);
            continue;
        };
        if w == "end" {
            break;
        }
        c.advance();
        match w.as_str() {
            "opaque" => {}
            "contour" => {
                if let Some(call) = c.shader_call_or_named("the contour shader", &r.raw.shaders) {
                    super::param_paths::record(c, &call, Some(".contour"), &mut values);
                    frame_fade = super::contours::frame_fade(c, &call);
                    contour = match frame_fade {
                        None => super::contours::material_shader(c, &call),
                        Some(_) => None,
                    };
                }
            }
            "volume" => {
                if let Some(call) = c.shader_call_or_named("the volume shader", &r.raw.shaders) {
                    values.record(".interior", c.located(call.pos));
                    interior = super::volumes::volume(c, &call, "material");
                }
            }
            "displace"
                if c.peek().is_some_and(|t| {
                    matches!(&t.tok, Tok::Str(s) if s == super::statements::TUTORIAL_DISPLACEMENT)
                }) && r
                    .raw
                    .linked
                    .iter()
                    .any(|l| l == super::statements::TUTORIAL_DISPLACEMENT) =>
            {
                if let Some(call) = c.shader_call_or_named("the displace shader", &r.raw.shaders) {
                    displace = super::displace::tutorial_displacement(c, &call);
                }
            }
            "shadow" => {
                if let Some(call) = c.shader_call_or_named("the shadow shader", &r.raw.shaders) {
                    values.record(".shadow", c.located(call.pos));
                    shadow = super::material_shaders::shadow(c, &call, &r.raw.shaders);
                }
            }
            "environment" => {
                if let Some(call) = c.shader_call_or_named("the environment shader", &r.raw.shaders) {
                    values.record(".environment", c.located(call.pos));
                    environment = super::material_shaders::environment(
                        c,
                        &call,
                        &r.raw.shaders,
                        &r.raw.linked,
                    );
                }
            }
            "photon" | "displace" => {
                if let Some(photon) = c.shader_call_or_named(&format!("the {w} shader"), &r.raw.shaders) {
                    let n = &photon.name;
                    if w == "photon" && is_photon_twin(&call.name, n) {
                        // Photons scatter through the material's own BSDF: what the twin does.
                        continue;
                    }
                    let msg = match w.as_str() {
                        "photon" => format!("photon shader \"{n}\" is read but not yet mapped"),
                        _ => format!("displace shader \"{n}\" is not mapped: objects with this material render undisplaced"),
                    };
                    c.warn(photon.pos, msg);
                }
            }
            other => {
                let mut p =
                    Problem::error(t.pos, format!("unknown material statement \"{other}\""));
                if let Some(s) = closest(other, MATERIAL.iter().copied()) {
                    p = p.with_help(format!("did you mean \"{s}\"?"));
                }
                c.report(p);
                c.skip_arguments();
            }
        }
    }
    let statements = c.record(start);
    c.expect_end("material", open);
    let Some((shader, lights, exclusive, bind)) = mapped else {
        return;
    };
    if fresh {
        incremental::keep(r, &name, "material", head, statements);
        let desc = MaterialDesc {
            name: name.clone(),
            shader,
            two_sided: false,
            emission: (0.0, 0.0, 0.0),
            bind,
            bump: None,
            interior,
            lights: None,
            shadow,
            environment,
            contour,
            photon: None,
        };
        r.raw.materials.push((
            name,
            RawMaterial {
                at: c.located(open),
                desc,
                lights,
                exclusive,
                frame_fade,
                displace,
                values,
            },
        ));
    }
}

/// `declare phenomenon type "name" (…) shader … root = "…" … end declare`, or `declare
/// shader … end declare` (a native shader's declaration: skipped).
pub fn declare(r: &mut Reader, c: &mut Cursor, open: Pos) {
    if !c.eat_word("phenomenon") {
        c.skip_to_end("declare", open);
        return;
    }
    // The result type: a word, or `struct { … }`.
    while matches!(
        c.peek(),
        Some(Token {
            tok: Tok::Word(_),
            ..
        })
    ) {
        c.advance();
    }
    if c.eat_punct('{') {
        while c.peek().is_some() && !c.eat_punct('}') {
            c.advance();
        }
    }
    let Some((name, pos)) = name_of(c, "phenomenon") else {
        c.skip_to_end("declare", open);
        return;
    };
    let fresh = r.define(c, &name, pos);
    // The interface parameter declarations.
    if c.eat_punct('(') {
        let mut depth = 1usize;
        while depth > 0 {
            match c.advance().map(|t| t.tok) {
                Some(Tok::Punct('(')) => depth += 1,
                Some(Tok::Punct(')')) => depth -= 1,
                None => break,
                _ => {}
            }
        }
    }
    let mut shaders = std::collections::HashMap::new();
    let mut root = None;
    loop {
        let Some(t) = c.peek().cloned() else {
            c.error(
                open,
                "\"declare\" block is not closed (expected \"end declare\")",
            );
            return;
        };
        match &t.tok {
            Tok::Word(w) if w == "end" => break,
            Tok::Word(w) if w == "shader" => {
                c.advance();
                let Some((sname, _)) = c.string("the shader name") else {
                    continue;
                };
                if let Some(call) = c.shader_call("the shader") {
                    shaders.insert(sname, call);
                }
            }
            Tok::Word(w) if w == "root" => {
                c.advance();
                c.eat_punct('=');
                root = c.string("the phenomenon root");
            }
            _ => {
                c.advance();
            }
        }
    }
    c.expect_end("declare", open);
    let Some((root, root_pos)) = root else {
        c.error(open, format!("phenomenon \"{name}\" has no root"));
        return;
    };
    let Some(call) = shaders.get(&root).cloned() else {
        c.error(
            root_pos,
            format!("phenomenon root \"{root}\" is not a shader of \"{name}\""),
        );
        return;
    };
    if fresh {
        r.raw.shaders.extend(shaders);
        r.raw.shaders.insert(name, call);
    }
}

/// `shader "name" "type" (…)`: a named shader other parameters refer to with `= "name"`.
pub fn named_shader(r: &mut Reader, c: &mut Cursor) {
    let Some((name, pos)) = c.string("the shader name") else {
        return;
    };
    let fresh = r.define(c, &name, pos);
    let earlier = incremental::earlier_body(r, "shader");
    let Some((call, head)) = incremental::head_call(r, c, earlier.as_ref(), "the shader", false)
    else {
        return;
    };
    if fresh {
        incremental::keep(r, &name, "shader", head, Default::default());
        r.raw.shaders.insert(name, call);
    }
}

/// `color|scalar|vector texture "name" [local] [filter [s]] "file"`: an image file that
/// `mib_texture_lookup` reads by name (the file relative to the declaring `.mi` file).
pub fn texture(r: &mut Reader, c: &mut Cursor) {
    c.eat_word("texture");
    let Some((name, pos)) = c.string("the texture name") else {
        return;
    };
    let fresh = r.define(c, &name, pos);
    c.eat_word("local");
    if c.eat_word("filter") && c.at_number() {
        let _ = c.number("the filter scale");
    }
    if !c.at_string() {
        let at = c.pos();
        c.error(
            at,
            format!("texture \"{name}\" needs an image file (a procedural texture is not mapped)"),
        );
        c.skip_arguments();
        return;
    }
    let Some((file, at)) = c.string("the texture file") else {
        return;
    };
    if fresh {
        // Image files are relative to the root scene file: rebase an included file's.
        let root = r.root.file.parent().unwrap_or(std::path::Path::new(""));
        let written_in = c.located(at).file;
        let file = match written_in.parent() {
            Some(dir) if dir != root => {
                let full = dir.join(&file);
                full.strip_prefix(root)
                    .map_or(full.clone(), std::path::Path::to_path_buf)
                    .to_string_lossy()
                    .into_owned()
            }
            _ => file,
        };
        r.raw.textures.insert(name, (file, c.located(at)));
    }
}
