//! The feature switches of an `options` block: `lens`, `volume`, `geometry`, `displace` and
//! `output` `on|off` become `options.disable` (see [`crate::features::Feature`]); the last
//! statement for a feature wins. Also `diagnostic samples on|off` (`options.diagnostic`). Shaders of a switched-off kind are still read and mapped
//! (the switch is a run input, so `stagelight convert` keeps both).

use super::super::rib::Pos;
use super::cursor::Cursor;
use super::lexer::Tok;
use crate::scene::desc::{DiagnosticDesc, FeatureDesc, OptionsDesc};

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

/// `diagnostic samples on|off` after the word `diagnostic` (at `at`) sets
/// `options.diagnostic`; the other diagnostic modes (`grid`, `photon`, `bsp`, …) are
/// read and warned.
pub fn diagnostic(c: &mut Cursor, at: Pos, desc: &mut OptionsDesc) {
    if c.eat_word("samples") {
        desc.diagnostic = c.switch().then_some(DiagnosticDesc::Samples);
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
        format!("\"diagnostic {mode}\" is read but not mapped (only \"diagnostic samples\" is)"),
    );
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
