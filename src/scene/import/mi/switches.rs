//! The feature switches of an `options` block: `lens`, `volume`, `geometry`, `displace` and
//! `output` `on|off` become `options.disable` (see [`crate::features::Feature`]); the last
//! statement for a feature wins. Also `diagnostic samples|grid|photon|bsp …` (`options.diagnostic`). Shaders of a switched-off kind are still read and mapped
//! (the switch is a run input, so `stagelight convert` keeps both).

use super::super::located::Pos;
use super::cursor::Cursor;
use super::lexer::Tok;
use crate::scene::desc::{
    BvhQuantityDesc, DiagnosticDesc, FeatureDesc, GridSpaceDesc, OptionsDesc, PhotonQuantityDesc,
};

/// Whether `word` is a feature switch of `options`.
pub fn is_switch(word: &str) -> bool {
    feature(word).is_some()
}

/// The feature mental ray's option `word` switches.
fn feature(word: &str) -> Option<FeatureDesc> {
    Some(match word {
        "lens" => FeatureDesc::Lens,
        "volume" => FeatureDesc::Volume,
        "geometry" => FeatureDesc::Geometry,
        "displace" => FeatureDesc::Displacement,
        "output" => FeatureDesc::Output,
        _ => return None,
    })
}

/// `lens|volume|geometry|displace|output [on|off]` after the word (`on` when absent).
pub fn switch(c: &mut Cursor, word: &str, desc: &mut OptionsDesc) {
    let Some(f) = feature(word) else { return };
    let on = c.switch();
    desc.disable.retain(|d| *d != f);
    if !on {
        desc.disable.push(f);
    }
}

/// `diagnostic samples on|off`, `diagnostic grid off|object|world|camera S`,
/// `diagnostic photon off|density|irradiance N` and `diagnostic bsp off|depth|size` after the
/// word `diagnostic` (at `at`) set `options.diagnostic`; the other diagnostic modes
/// (`finalgather`, …) are read and warned.
pub fn diagnostic(c: &mut Cursor, at: Pos, desc: &mut OptionsDesc) {
    if c.eat_word("samples") {
        desc.diagnostic = c.switch().then_some(DiagnosticDesc::Samples);
        return;
    }
    if c.eat_word("grid") {
        let space = if c.eat_word("off") {
            desc.diagnostic = None;
            return;
        } else if c.eat_word("object") {
            GridSpaceDesc::Object
        } else if c.eat_word("world") {
            GridSpaceDesc::World
        } else if c.eat_word("camera") {
            GridSpaceDesc::Camera
        } else {
            let p = c.pos();
            c.error(
                p,
                format!(
                    "expected off, object, world or camera after diagnostic grid, found {}",
                    found(c)
                ),
            );
            c.skip_arguments();
            return;
        };
        if let Some(size) = positive(c, "diagnostic grid size") {
            desc.diagnostic = Some(DiagnosticDesc::Grid { space, size });
        }
        return;
    }
    if c.eat_word("photon") {
        let quantity = if c.eat_word("off") {
            desc.diagnostic = None;
            return;
        } else if c.eat_word("density") {
            PhotonQuantityDesc::Density
        } else if c.eat_word("irradiance") {
            PhotonQuantityDesc::Irradiance
        } else {
            let p = c.pos();
            c.error(
                p,
                format!(
                    "expected off, density or irradiance after diagnostic photon, found {}",
                    found(c)
                ),
            );
            c.skip_arguments();
            return;
        };
        if let Some(max) = positive(c, "diagnostic photon maximum") {
            desc.diagnostic = Some(DiagnosticDesc::Photon { quantity, max });
        }
        return;
    }
    if c.eat_word("bsp") {
        let quantity = if c.eat_word("off") {
            desc.diagnostic = None;
            return;
        } else if c.eat_word("depth") {
            BvhQuantityDesc::Depth
        } else if c.eat_word("size") {
            BvhQuantityDesc::Size
        } else {
            let p = c.pos();
            c.error(
                p,
                format!(
                    "expected off, depth or size after diagnostic bsp, found {}",
                    found(c)
                ),
            );
            c.skip_arguments();
            return;
        };
        desc.diagnostic = Some(DiagnosticDesc::Bvh {
            quantity,
            max: None,
        });
        return;
    }
    let mode = match c.peek().map(|t| &t.tok) {
        Some(Tok::Word(w)) => w.clone(),
        _ => String::new(),
    };
    while matches!(c.peek().map(|t| &t.tok), Some(Tok::Word(w)) if DIAGNOSTIC_WORDS.contains(&w.as_str()))
    {
        c.advance();
        c.skip_arguments();
    }
    c.skip_arguments();
    c.warn(
        at,
        format!("\"diagnostic {mode}\" is read but not mapped (\"diagnostic samples\", \"grid\", \"photon\" and \"bsp\" are)"),
    );
}

/// A number > 0 for `what`, or a located error.
fn positive(c: &mut Cursor, what: &str) -> Option<f64> {
    let p = c.pos();
    let x = c.number(what)?;
    if !(x.is_finite() && x > 0.0) {
        c.error(p, format!("{what} must be > 0, found {x}"));
        return None;
    }
    Some(x)
}

fn found(c: &Cursor) -> String {
    c.peek()
        .map_or("the end of the file".into(), |t| t.tok.describe())
}

/// Words of the diagnostic modes that are read and skipped.
const DIAGNOSTIC_WORDS: &[&str] = &[
    "grid",
    "object",
    "world",
    "camera",
    "size",
    "photon",
    "density",
    "irradiance",
    "bsp",
    "depth",
    "finalgather",
    "off",
    "on",
];
