//! `Illuminate` on `AreaLightSource` handles. RenderMan switches an area light off for the
//! primitives that follow `Illuminate handle 0` (until `Illuminate handle 1` or the end of
//! the attribute block); stagelight's area light is the emission of its surfaces, which
//! lights every primitive or none. So the reader counts, per area light, the primitives
//! declared while it is off and those it lights (every other one but its own surfaces):
//! a light off for every primitive it could light is switched off for the whole scene (its
//! surfaces emit nothing); a light off for some primitives only stays on, with a located
//! warning at its first `Illuminate handle 0` naming both counts.

use std::collections::HashMap;

use super::super::located::{Pos, Problem};

/// One `AreaLightSource`.
#[derive(Debug, Clone)]
struct AreaLight {
    handle: String,
    /// The first `Illuminate handle 0` (file, position of the `0`).
    off_at: Option<(usize, Pos)>,
    /// Primitives declared while it was off.
    unlit: usize,
    /// Its own surfaces.
    own: usize,
}

/// The area lights of a file and the primitives they light.
#[derive(Debug, Clone, Default)]
pub struct AreaLights {
    lights: Vec<AreaLight>,
    handles: HashMap<String, usize>,
    /// Primitives placed so far.
    primitives: usize,
}

impl AreaLights {
    /// A new area light under `handle` (replacing an area light of the same handle).
    pub fn define(&mut self, handle: &str) -> usize {
        let id = self.lights.len();
        self.lights.push(AreaLight {
            handle: handle.to_string(),
            off_at: None,
            unlit: 0,
            own: 0,
        });
        self.handles.insert(handle.to_string(), id);
        id
    }

    /// `handle` now names a `LightSource`.
    pub fn forget(&mut self, handle: &str) {
        self.handles.remove(handle);
    }

    /// The area light `handle` names.
    pub fn id(&self, handle: &str) -> Option<usize> {
        self.handles.get(handle).copied()
    }

    /// `Illuminate` of area light `id` (`on`, the `onoff` value at `at`) on the list of area
    /// lights off for the primitives that follow.
    pub fn illuminate(&mut self, id: usize, on: bool, at: (usize, Pos), off: &mut Vec<usize>) {
        off.retain(|&l| l != id);
        if !on {
            off.push(id);
            self.lights[id].off_at.get_or_insert(at);
        }
    }

    /// Counts a primitive placed with the area lights `off` switched off, itself a surface of
    /// area light `emitter`.
    pub fn place(&mut self, emitter: Option<usize>, off: &[usize]) {
        self.primitives += 1;
        if let Some(l) = emitter.and_then(|e| self.lights.get_mut(e)) {
            l.own += 1;
        }
        for &id in off {
            if Some(id) != emitter {
                if let Some(l) = self.lights.get_mut(id) {
                    l.unlit += 1;
                }
            }
        }
    }

    /// The area lights off for every primitive they could light (their surfaces emit
    /// nothing), and a warning (file, problem) for each one off for some primitives only.
    pub fn finish(&self) -> (Vec<usize>, Vec<(usize, Problem)>) {
        let mut dark = Vec::new();
        let mut warnings = Vec::new();
        for (id, l) in self.lights.iter().enumerate() {
            let Some((file, at)) = l.off_at else { continue };
            if l.unlit == 0 {
                continue;
            }
            let lit = self.primitives - l.unlit - l.own;
            if lit == 0 {
                dark.push(id);
                continue;
            }
            let plural = |n: usize| if n == 1 { "primitive" } else { "primitives" };
            warnings.push((
                file,
                Problem::warning(
                    at,
                    format!(
                        "Illuminate cannot switch off area light {} for the {} {} declared \
                         while it is off: it lights {lit} other {}, and an area light's \
                         surfaces light every primitive or none",
                        l.handle,
                        l.unlit,
                        plural(l.unlit),
                        plural(lit)
                    ),
                )
                .with_help(
                    "it stays on for every primitive; it is switched off when every primitive \
                     but its own surfaces is declared while it is off",
                ),
            ));
        }
        (dark, warnings)
    }
}
