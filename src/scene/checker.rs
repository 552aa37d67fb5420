//! The two tools every check of a scene element uses: [`Item`] (an element of the merged
//! scene with its file, description path and source position) and [`Checker`] (records
//! errors about one element's values, located through its file's map, with the shared
//! finiteness, colour and matrix checks). Validation modules import these from here, so
//! none of them depends on another.

use glam::{DAffine3, DMat3, DVec3};

use super::desc::{M4, V3};
use super::diagnostics::Sources;
use super::import::SourcePos;
use super::message::Diagnostic;
use super::syntax::Helps;

/// One element of the merged scene: where it was written and what it says.
#[derive(Debug)]
pub struct Item<'a, T> {
    /// File index in [`Sources::files`] (whose map locates the values inside the element).
    pub file: usize,
    /// Path of the element in its file's description (`materials[3]`).
    pub path: String,
    /// Where the element itself was written, from its reader's map.
    pub pos: SourcePos,
    /// The element.
    pub desc: &'a T,
}

impl<'a, T> Item<'a, T> {
    /// The element at `path` of file `file`, located through the file's map.
    pub fn new(src: &Sources, file: usize, path: String, desc: &'a T) -> Self {
        Self {
            file,
            pos: src.pos(file, &path),
            path,
            desc,
        }
    }
}

impl<T> Item<'_, T> {
    /// Path of a value inside the element (`suffix` starts with `.` or `[`).
    pub fn at(&self, suffix: &str) -> String {
        format!("{}{suffix}", self.path)
    }
}

/// The brightest radiant value a scene may give (W/sr, W/m² or W/(sr·m²) per channel): the
/// renderer's arithmetic is f32, and radiance divided by a small sampling density or summed
/// over samples overflows past ~1e30 (light was lost silently). The Sun's radiance is ~2e7.
pub const MAX_RADIANT: f64 = 1e20;

const RADIANT_HELP: &str = "radiant values above 1e20 overflow f32 arithmetic in sampling; scale the scene's light down (the camera's imager exposure can scale the image back)";

/// Records errors about the values of one element.
pub struct Checker<'s> {
    /// Where errors go.
    pub src: &'s mut Sources,
    /// File of the element.
    pub file: usize,
}

impl Checker<'_> {
    /// Records an error at `path`.
    pub fn error(&mut self, path: &str, message: impl Into<String>) {
        self.src.error(self.file, path, message, None);
    }

    /// Records a warning at `path`, with `help`.
    pub fn warn(&mut self, path: &str, message: impl Into<String>, help: &str) {
        let pos = self.src.pos(self.file, path);
        let diagnostic = Diagnostic::at(pos, message, Some(help.into()));
        self.src.push_warning(self.file, diagnostic);
    }

    /// Whether `x` is finite and fits in f32 (every value ends up in f32); reports it at
    /// `path` if not.
    pub fn finite(&mut self, path: &str, what: &str, x: f64) -> bool {
        if !x.is_finite() {
            self.error(path, format!("{what} must be a finite number, found {x}"));
            false
        } else if x.abs() > f64::from(f32::MAX) {
            self.error(path, format!("{what} {x:e} is beyond the f32 range"));
            false
        } else {
            true
        }
    }

    /// A finite vector (each non-finite component reported at `path[k]`).
    pub fn v3(&mut self, path: &str, what: &str, v: V3) -> Option<DVec3> {
        let ok = [v.0, v.1, v.2]
            .iter()
            .enumerate()
            .fold(true, |ok, (k, &x)| {
                self.finite(&format!("{path}[{k}]"), what, x) && ok
            });
        ok.then(|| DVec3::new(v.0, v.1, v.2))
    }

    /// A finite vector with no negative component.
    pub fn colour(&mut self, path: &str, what: &str, v: V3) -> Option<DVec3> {
        let c = self.v3(path, what, v)?;
        let mut ok = true;
        for (k, x) in c.to_array().into_iter().enumerate() {
            if x < 0.0 {
                self.negative(&format!("{path}[{k}]"), what, x);
                ok = false;
            }
        }
        ok.then_some(c)
    }

    /// A radiant quantity (a light's colour × intensity, an emission, an environment's
    /// radiance) no brighter than [`MAX_RADIANT`] in any channel; reports it at `path` if it is.
    pub fn radiant(&mut self, path: &str, what: &str, v: DVec3) -> Option<DVec3> {
        let brightest = v.max_element();
        if brightest > MAX_RADIANT {
            self.src.error(
                self.file,
                path,
                format!("{what} {brightest:e} is brighter than stagelight carries (at most {MAX_RADIANT:e})"),
                Some(RADIANT_HELP.into()),
            );
            return None;
        }
        Some(v)
    }

    /// A finite, non-negative number.
    pub fn non_negative(&mut self, path: &str, what: &str, x: f64) -> Option<f64> {
        if !self.finite(path, what, x) {
            return None;
        }
        if x < 0.0 {
            self.negative(path, what, x);
            return None;
        }
        Some(x)
    }

    /// Reports the negative `x` of `what` at `path`, with what to write instead.
    fn negative(&mut self, path: &str, what: &str, x: f64) {
        self.src.error(
            self.file,
            path,
            format!("{what} must not be negative, found {x}"),
            Some(format!(
                "{what} takes 0 or more: write {} if only the sign is wrong",
                -x
            )),
        );
    }

    /// A finite row-major matrix (each non-finite entry reported at `path[r][c]`).
    pub fn matrix(&mut self, path: &str, what: &str, m: &M4) -> bool {
        let mut ok = true;
        for (r, row) in m.iter().enumerate() {
            for (c, &x) in row.iter().enumerate() {
                ok &= self.finite(&format!("{path}[{r}][{c}]"), what, x);
            }
        }
        ok
    }

    /// The affine transform of a row-major matrix whose last row must be `(0, 0, 0, 1)`.
    pub fn affine(&mut self, path: &str, what: &str, m: &M4) -> Option<DAffine3> {
        if !self.matrix(path, what, m) {
            return None;
        }
        // A bottom row a general inverse left a few bits off (0.9999999999999999) is
        // (0, 0, 0, 1): the rows above are the transform.
        let exact = [0.0, 0.0, 0.0, 1.0];
        if (0..4).any(|j| (m[3][j] - exact[j]).abs() > BOTTOM_ROW_TOLERANCE) {
            let neutral = "an affine transform's last row is (0, 0, 0, 1): a projective matrix cannot place anything";
            let help = self.src.syntax(self.file).help_each(Helps {
                ron: "the rows are written in order with the translation in the last column, \
                      `((a, b, c, tx), (d, e, f, ty), (g, h, i, tz), (0, 0, 0, 1))`: a matrix \
                      written column by column (translation in the last row) must be transposed",
                mi: neutral,
                rib: neutral,
                gltf: neutral,
            });
            self.src.error(
                self.file,
                &format!("{path}[3]"),
                format!(
                    "the last row of a {what} must be (0, 0, 0, 1), found {}",
                    tuple(&m[3])
                ),
                Some(help),
            );
            return None;
        }
        let col = |j: usize| DVec3::new(m[0][j], m[1][j], m[2][j]);
        Some(DAffine3::from_mat3_translation(
            DMat3::from_cols(col(0), col(1), col(2)),
            col(3),
        ))
    }
}

/// How far an entry of an affine matrix's bottom row may be from `(0, 0, 0, 1)`'s: what a
/// general 4×4 inverse leaves (a few units in the last place), not a projective row.
const BOTTOM_ROW_TOLERANCE: f64 = 1e-9;

fn tuple(row: &[f64; 4]) -> String {
    format!("({}, {}, {}, {})", row[0], row[1], row[2], row[3])
}
