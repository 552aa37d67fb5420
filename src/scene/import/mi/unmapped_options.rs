//! mental ray's standard `options` statements that stagelight reads but does not map: each
//! is read with its arguments (numbers, strings and the words it takes, each once) and gives one
//! located warning, so a scene exported with them renders instead of failing on an "unknown
//! option". The reason says what stagelight does instead where that is not obvious
//! (`shutter 0.5`: motion blur is not rendered).

use super::super::located::Pos;
use super::cursor::Cursor;

/// One statement: its first word, the words that may follow it, and why it is not mapped.
struct Unmapped {
    name: &'static str,
    words: &'static [&'static str],
    why: Option<&'static str>,
}

const MOTION: Option<&str> = Some("motion blur is not rendered");
const ACCELERATION: Option<&str> = Some("stagelight builds its own bounding volume hierarchy");
const IMAGE: Option<&str> = Some("stagelight writes the image as its outputs describe");

const UNMAPPED: &[Unmapped] = &[
    Unmapped {
        name: "filter",
        words: &["box", "triangle", "gauss", "mitchell", "lanczos", "clip"],
        why: None,
    },
    Unmapped {
        name: "scanline",
        words: &["opengl", "rapid", "raycast"],
        why: None,
    },
    Unmapped {
        name: "jitter",
        words: &[],
        why: None,
    },
    Unmapped {
        name: "shutter",
        words: &[],
        why: MOTION,
    },
    Unmapped {
        name: "motion",
        words: &["steps"],
        why: MOTION,
    },
    Unmapped {
        name: "hardware",
        words: &["all", "cg", "opengl", "fast", "force"],
        why: Some("stagelight renders on the CPU"),
    },
    Unmapped {
        name: "acceleration",
        words: &["bsp", "bsp2", "grid", "large"],
        why: ACCELERATION,
    },
    Unmapped {
        name: "bsp",
        words: &["size", "depth", "memory", "shadow"],
        why: ACCELERATION,
    },
    Unmapped {
        name: "grid",
        words: &["size", "resolution", "depth"],
        why: ACCELERATION,
    },
    Unmapped {
        name: "task",
        words: &["size"],
        why: Some("stagelight chooses its own tiles"),
    },
    Unmapped {
        name: "lightmap",
        words: &["only"],
        why: Some("lightmap shaders are not run"),
    },
    Unmapped {
        name: "shadowmap",
        words: &["motion", "rebuild", "only", "merge"],
        why: Some("shadows are ray traced"),
    },
    Unmapped {
        name: "samplelock",
        words: &[],
        why: None,
    },
    Unmapped {
        name: "field",
        words: &["even", "odd"],
        why: Some("whole frames are rendered"),
    },
    Unmapped {
        name: "photonvol",
        words: &["accuracy"],
        why: Some("volume photons are not traced"),
    },
    Unmapped {
        name: "autovolume",
        words: &[],
        why: None,
    },
    Unmapped {
        name: "luminance",
        words: &["weight"],
        why: None,
    },
    Unmapped {
        name: "dither",
        words: &[],
        why: IMAGE,
    },
    Unmapped {
        name: "premultiply",
        words: &[],
        why: IMAGE,
    },
    Unmapped {
        name: "gamma",
        words: &[],
        why: IMAGE,
    },
    Unmapped {
        name: "colorclip",
        words: &["rgb", "alpha", "raw"],
        why: IMAGE,
    },
    Unmapped {
        name: "desaturate",
        words: &[],
        why: IMAGE,
    },
];

/// Whether `word` starts a standard option that is read and not mapped.
pub fn is_unmapped(word: &str) -> bool {
    UNMAPPED.iter().any(|u| u.name == word)
}

/// Every such option's name (for did-you-mean).
pub fn names() -> impl Iterator<Item = &'static str> {
    UNMAPPED.iter().map(|u| u.name)
}

/// Reads the arguments of the option `word` (at `at`; the word already taken) and warns that
/// it is not mapped.
pub fn read(c: &mut Cursor, word: &str, at: Pos) {
    let Some(u) = UNMAPPED.iter().find(|u| u.name == word) else {
        return;
    };
    // Each word is taken once: `acceleration large bsp` followed by `bsp size 10` is two
    // statements.
    let mut taken: Vec<&str> = Vec::new();
    loop {
        c.skip_arguments();
        let Some(&w) = u.words.iter().find(|w| !taken.contains(w) && c.at_word(w)) else {
            break;
        };
        c.advance();
        taken.push(w);
    }
    let message = match u.why {
        Some(why) => format!("option \"{word}\" is read but not mapped: {why}"),
        None => format!("option \"{word}\" is read but not mapped"),
    };
    c.warn(at, message);
}
