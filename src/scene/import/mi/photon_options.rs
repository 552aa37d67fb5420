//! The photon statements of an `options` block, mapped onto the description's photon maps
//! (`options.caustics`, `options.global_illumination`, see `docs/scene-format.md`):
//!
//! * `caustic on|off`, `globillum on|off` turn a map on or off (mental ray: off by default);
//! * `caustic accuracy N [r]`, `globillum accuracy N [r]`: photons per estimate (`gather`)
//!   and the largest gather radius (`radius`; 0 or absent: automatic);
//! * `caustic filter box|cone [k]|gauss` (cone's `k` defaults to mental ray's 1.1);
//! * `finalgather accuracy [view] N [maxr [minr]]`: final-gather rays (`final_gather`);
//!   `finalgather on|off` only warns where it cannot hold (the global-illumination map is
//!   always final-gathered here, and final gathering needs that map);
//! * `photonmap file "…"` and `photonmap rebuild on|off`: `options.photon_map` (the maps
//!   kept in that file between runs);
//! * `photon trace depth r [t [s]]`: `options.photon_depth` (most reflections `r`,
//!   refractions `t`, default `r`, and their sum `s`, default `r + t`).
//!
//! Accuracy and filter statements keep their values whether or not the map is on, as in
//! mental ray; the photon counts come from the lights (`caustic photons N`) or the map's
//! default.

use super::super::located::Pos;
use super::cursor::Cursor;
use super::lexer::Tok;
use super::value_positions::ValuePositions;
use crate::scene::desc::{
    OptionsDesc, PhotonDepthDesc, PhotonFilterDesc, PhotonMapDesc, PhotonMapFileDesc,
};

/// mental ray's default cone filter constant.
const DEFAULT_CONE_K: f64 = 1.1;

/// What the photon statements of one `options` block said so far.
#[derive(Debug, Clone, Default)]
pub struct PhotonOptions {
    caustic: Map,
    globillum: Map,
    /// `finalgather on|off` and where it was written.
    final_gather: Option<(bool, Pos)>,
    /// `photonmap file "…"` and where the file name was written.
    file: Option<(String, Pos)>,
    /// `photonmap rebuild on|off` and where it was written.
    rebuild: Option<(bool, Pos)>,
    /// `photon trace depth …`.
    depth: Option<PhotonDepthDesc>,
}

/// One map: switched on, and its knobs.
#[derive(Debug, Clone, Default)]
struct Map {
    on: bool,
    desc: PhotonMapDesc,
    /// Where its values were written, by description path below the map (`.gather`).
    values: Vec<(&'static str, Pos)>,
}

impl PhotonOptions {
    /// `caustic …` after the word `caustic` (at `at`).
    pub fn caustic(&mut self, c: &mut Cursor, at: Pos) {
        if c.eat_word("filter") {
            let filter = if c.eat_word("box") {
                PhotonFilterDesc::Box
            } else if c.eat_word("gauss") {
                PhotonFilterDesc::Gauss
            } else if c.eat_word("cone") {
                let k = if c.at_number() {
                    c.number("caustic filter cone").unwrap_or(DEFAULT_CONE_K)
                } else {
                    DEFAULT_CONE_K
                };
                PhotonFilterDesc::Cone { k }
            } else {
                let (p, found) = found(c);
                c.error(
                    p,
                    format!("expected box, cone or gauss after caustic filter, found {found}"),
                );
                // The misspelt filter name is its argument: skip it with its numbers.
                if c.peek()
                    .is_some_and(|t| matches!(&t.tok, Tok::Word(w) if w != "end"))
                {
                    c.advance();
                }
                c.skip_arguments();
                return;
            };
            self.caustic.desc.filter = filter;
            return;
        }
        map_statement(&mut self.caustic, c, at, "caustic");
    }

    /// `globillum …` after the word `globillum` (at `at`).
    pub fn globillum(&mut self, c: &mut Cursor, at: Pos) {
        map_statement(&mut self.globillum, c, at, "globillum");
    }

    /// `finalgather …` after the word `finalgather` (at `at`).
    pub fn final_gather(&mut self, c: &mut Cursor, at: Pos) {
        if c.eat_word("accuracy") {
            c.eat_word("view");
            let value = c.pos();
            let Some(rays) = c.count("finalgather accuracy") else {
                return;
            };
            if rays == 0 {
                c.error(
                    value,
                    "finalgather accuracy must be at least 1 ray, found 0",
                );
                c.skip_arguments();
                return;
            }
            self.globillum.desc.final_gather = rays;
            self.globillum.values.push((".final_gather", value));
            if c.at_number() {
                c.skip_arguments();
                c.warn(
                    at,
                    "finalgather radii are not mapped: final-gather rays look up the \
                     global-illumination map at every distance",
                );
            }
            return;
        }
        for w in ["only", "fastlookup"] {
            if c.eat_word(w) {
                c.warn(at, format!("\"finalgather {w}\" is read but not mapped"));
                return;
            }
        }
        self.final_gather = Some((c.switch(), at));
    }

    /// `photonmap file "…"` / `photonmap rebuild on|off` after the word `photonmap`.
    pub fn photon_map(&mut self, c: &mut Cursor, at: Pos) {
        if c.eat_word("file") {
            if let Some(file) = c.string("the photon map file") {
                self.file = Some(file);
            }
        } else if c.eat_word("rebuild") {
            self.rebuild = Some((c.switch(), at));
        } else {
            let (p, found) = found(c);
            c.error(
                p,
                format!("expected file or rebuild after photonmap, found {found}"),
            );
            c.skip_arguments();
        }
    }

    /// `photon trace depth r [t [s]]` after the word `photon` (at the word `trace`).
    pub fn trace_depth(&mut self, c: &mut Cursor) {
        c.eat_word("trace");
        if !c.eat_word("depth") {
            let (p, found) = found(c);
            c.error(
                p,
                format!("expected depth after photon trace, found {found}"),
            );
            c.skip_arguments();
            return;
        }
        let what = "photon trace depth";
        let Some(r) = c.count(what) else {
            return;
        };
        let t = if c.at_number() {
            let Some(t) = c.count(what) else {
                return;
            };
            t
        } else {
            r
        };
        let sum = if c.at_number() {
            let Some(s) = c.count(what) else {
                return;
            };
            s
        } else {
            r.saturating_add(t)
        };
        self.depth = Some(PhotonDepthDesc {
            reflection: Some(r),
            refraction: Some(t),
            sum: Some(sum),
        });
    }

    /// Writes the maps that are on into `desc`, warning where `finalgather` cannot hold;
    /// where their values were written goes into `values` (below `options`).
    pub fn apply(self, c: &mut Cursor, desc: &mut OptionsDesc, values: &mut ValuePositions) {
        if let Some(depth) = self.depth {
            desc.photon_depth = Some(depth);
        }
        for (map, path) in [
            (&self.caustic, ".caustics"),
            (&self.globillum, ".global_illumination"),
        ] {
            if map.on {
                for (value, at) in &map.values {
                    values.record(format!("{path}{value}"), c.located(*at));
                }
            }
        }
        match (self.file, self.rebuild) {
            (Some((file, at)), rebuild) => {
                values.record(".photon_map.file", c.located(at));
                desc.photon_map = Some(PhotonMapFileDesc {
                    file,
                    rebuild: rebuild.is_some_and(|(on, _)| on),
                });
            }
            (None, Some((_, at))) => c.warn(
                at,
                "\"photonmap rebuild\" without \"photonmap file\" has no effect",
            ),
            (None, None) => {}
        }
        desc.caustics = self.caustic.on.then_some(self.caustic.desc);
        desc.global_illumination = self.globillum.on.then_some(self.globillum.desc);
        match self.final_gather {
            Some((true, at)) if !self.globillum.on => c.warn(
                at,
                "final gathering uses the global-illumination photon map here; add \
                 \"globillum on\" to gather",
            ),
            Some((false, at)) if self.globillum.on => c.warn(
                at,
                "\"finalgather off\" is not mapped: the global-illumination map is always \
                 final-gathered",
            ),
            _ => {}
        }
    }
}

/// `on|off` or `accuracy N [r]` of the map `name`.
fn map_statement(map: &mut Map, c: &mut Cursor, at: Pos, name: &str) {
    if c.eat_word("accuracy") {
        let what = format!("{name} accuracy");
        let value = c.pos();
        let Some(n) = c.count(&what) else {
            return;
        };
        if n < 2 {
            c.error(
                value,
                format!("{what} must be at least 2 photons per estimate, found {n}"),
            );
            c.skip_arguments();
            return;
        }
        map.desc.gather = n;
        map.values.push((".gather", value));
        if c.at_number() {
            let p = c.pos();
            let Some(r) = c.number(&what) else {
                return;
            };
            if !(r.is_finite() && r >= 0.0) {
                c.error(p, format!("the {what} radius must be ≥ 0, found {r}"));
                c.skip_arguments();
                return;
            }
            map.desc.radius = r;
            map.values.push((".radius", p));
        }
        return;
    }
    if c.at_number() {
        // `caustic N` / `globillum N` in options: mental ray's mode; 0 is off.
        let Some(mode) = c.count(name) else {
            return;
        };
        map.on = mode != 0;
        return;
    }
    let on = c.switch();
    map.on = on;
    if c.at_number() {
        c.skip_arguments();
        c.warn(at, format!("the arguments after \"{name}\" are not mapped"));
    }
}

fn found(c: &Cursor) -> (Pos, String) {
    (
        c.pos(),
        c.peek()
            .map_or("the end of the file".into(), |t| t.tok.describe()),
    )
}
