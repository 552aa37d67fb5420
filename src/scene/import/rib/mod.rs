//! The RenderMan RIB reader: ASCII RIB → the format-neutral [`SceneDesc`] with a source
//! position for every element and value, plus located warnings for what it does not map.
//!
//! One module per step: [`lexer`] (tokens with `line:column`), [`parse`] (requests and
//! their arguments), [`params`] (parameter lists, inline declarations, `Declare`),
//! [`state`] (the graphics state: attribute and transform stacks), [`build`] (request by
//! request onto the description), with the request families in [`shaders`] (surfaces,
//! displacements, lights), [`geometry`] (quadrics, polygons, patches, NURBS, subdivision
//! meshes; [`revolve`]: paraboloids and hyperboloids) and [`camera`] (options, the camera
//! and its outputs).
//!
//! **Conventions.** RenderMan's camera space is left-handed (+x right, +y up, +z into the
//! screen) and the transformation current at `WorldBegin` is camera-from-world. stagelight's
//! camera looks down −z of a right-handed frame, so the reader mirrors the world through
//! z = 0 (world `(x, y, z)` is written `(x, y, −z)`) whenever the camera transformation is a
//! proper motion, which makes the camera a proper rotation again; a camera transformation
//! that already mirrors (`Scale 1 1 -1`) needs no mirror. Every primitive keeps its RIB
//! object space; its instance carries the matrix `mirror · world-from-object`. `Rotate`
//! takes degrees, light-shader angles (`coneangle`, `conedeltaangle`) radians; missing
//! parameters take the values of the RenderMan Interface Specification 3.2.

pub mod build;
pub mod camera;
pub mod geometry;
pub mod lexer;
pub mod params;
pub mod parse;
pub mod revolve;
pub mod shaders;
pub mod state;

use std::path::{Path, PathBuf};

use super::{PathTable, ReadScene, SourcePos};
use crate::scene::desc::SceneDesc;
use crate::scene::message::Diagnostic;

/// A 1-based line and column (columns count characters).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Pos {
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

impl Default for Pos {
    fn default() -> Self {
        Self { line: 1, column: 1 }
    }
}

/// A problem found while reading, located in the file being read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// Where.
    pub pos: Pos,
    /// What.
    pub message: String,
    /// A suggestion.
    pub help: Option<String>,
    /// A warning (something ignored) rather than an error.
    pub warning: bool,
}

impl Problem {
    /// An error at `pos`.
    pub fn error(pos: Pos, message: impl Into<String>) -> Self {
        Self {
            pos,
            message: message.into(),
            help: None,
            warning: false,
        }
    }

    /// A warning at `pos`.
    pub fn warning(pos: Pos, message: impl Into<String>) -> Self {
        Self {
            warning: true,
            ..Self::error(pos, message)
        }
    }

    /// The same problem with a `help:` line.
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

/// A position in one of the files read (the root or a `ReadArchive`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Located {
    /// The file, as the user named it (archives joined to the reading file's folder).
    pub file: PathBuf,
    /// Line and column.
    pub pos: Pos,
}

/// A problem with its file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LocatedProblem {
    /// The file.
    pub file: PathBuf,
    /// The problem.
    pub problem: Problem,
}

impl std::fmt::Display for LocatedProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let p = &self.problem;
        write!(
            f,
            "{}:{}:{}: {}: {}",
            self.file.display(),
            p.pos.line,
            p.pos.column,
            if p.warning { "warning" } else { "error" },
            p.message
        )?;
        if let Some(h) = &p.help {
            write!(f, "\n  help: {h}")?;
        }
        Ok(())
    }
}

/// What the reader made of one RIB file.
#[derive(Debug, Clone)]
pub struct RibScene {
    /// The description.
    pub desc: SceneDesc,
    /// Where each element and value was written, by description path
    /// (`objects[3].mesh.Sphere.radius`), in the order recorded.
    pub paths: Vec<(String, Located)>,
    /// What was ignored, located.
    pub warnings: Vec<LocatedProblem>,
    /// The `ReadArchive` files read (the root file left out).
    pub archives: Vec<std::path::PathBuf>,
}

/// Reads the RIB file `path` whose contents are `bytes`. `ReadArchive` files are read from
/// disk relative to `path`. On failure, every error found (warnings left out).
pub fn read_rib(path: &Path, bytes: &[u8]) -> Result<RibScene, Vec<LocatedProblem>> {
    build::Builder::run(path, bytes)
}

/// The [`super::ReadFn`] of `.rib`: [`read_rib`] with its positions in a [`PathTable`].
pub fn read(path: &Path, bytes: &[u8]) -> Result<ReadScene, Vec<Diagnostic>> {
    let diagnostic = |p: LocatedProblem| Diagnostic {
        file: p.file,
        line: p.problem.pos.line,
        column: p.problem.pos.column,
        message: p.problem.message,
        help: p.problem.help,
    };
    let scene =
        read_rib(path, bytes).map_err(|e| e.into_iter().map(diagnostic).collect::<Vec<_>>())?;
    let mut table = PathTable::default();
    for (p, at) in scene.paths {
        table.insert(
            p,
            SourcePos {
                file: at.file,
                line: at.pos.line,
                column: at.pos.column,
            },
        );
    }
    Ok(ReadScene {
        desc: scene.desc,
        map: table.into_map(path),
        warnings: scene.warnings.into_iter().map(diagnostic).collect(),
        read_files: scene.archives,
    })
}
